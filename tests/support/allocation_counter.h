// Counts heap allocations through operator new between start and stop: a
// test that links this replaces the global operator new (not under ASan,
// which brings its own; there the count stays 0 and tests skip the check).
#pragma once

namespace candela::test {

// Whether the count means anything in this build.
bool allocations_counted();
void start_counting_allocations();
// operator new calls since start_counting_allocations().
long stop_counting_allocations();

// How many times `run()` called operator new.
template <class Run>
long allocations_during(Run&& run) {
  start_counting_allocations();
  run();
  return stop_counting_allocations();
}

}  // namespace candela::test
