#!/bin/sh
# expect-status.sh WANT NEEDS CMD...: runs CMD and succeeds when it exits with
# WANT. NEEDS is a folder the command reads (the shared clips): absent, the test
# is skipped (77); "-" for none.
want=$1 needs=$2
shift 2
if [ "$needs" != "-" ] && [ ! -d "$needs" ]; then
  echo "skipped: $needs is not here (the shared clips stay out of the repository)"
  exit 77
fi
"$@" 2>&1
got=$?
[ "$got" -eq 77 ] && exit 77  # the command itself found something missing
if [ "$got" -ne "$want" ]; then
  echo "expected exit status $want, got $got: $*"
  exit 1
fi
exit 0
