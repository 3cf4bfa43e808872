// Small parsers for the fluid subcommands' option values. Each throws
// std::invalid_argument with a message naming the option and what it expects.
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "fluid_solver.h"

namespace candela::fluid {

// Runs a subcommand's work (returning its exit status); a bad value found on
// the way (std::invalid_argument from the parsers here) becomes
// "candela-tool NAME: WHAT" on stderr and exit status 2.
template <class Work>
int bad_values_exit(const char* name, Work&& work) {
  try {
    return work();
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "candela-tool %s: %s\n", name, e.what());
    return 2;
  }
}

// "WxH", e.g. "128x128".
void parse_size(const std::string& option, const std::string& text, int& w, int& h);
// "x=0.5,y=0.05,rx=0.04,ry=0.03,rate=20000,temp=1900,flicker=0.3,hz=6"; keys
// may be left out (defaults from HeatSource).
HeatSource parse_source(const std::string& text);
// "T:S[,T:S...]" seconds:cells-per-second.
std::vector<WindKey> parse_wind(const std::string& text);
// The command line as one string, for manifests.
std::string join_command(int argc, char** argv);

}  // namespace candela::fluid
