"""What the whole-program test scripts share (tests/*/*.py, on the host and
inside the virtual board, which sees the checkout at the same path):
check() prints one line per assertion and keeps the failures in FAILED;
wait_for() polls observable state against a deadline -- never a sleep as
synchronisation.

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__))), "support"))
    from checks import FAILED, check, wait_for
    ...
    run_case(CASE, globals())   # calls case_CASE(), prints the verdict, exits
"""
import sys
import time

FAILED = []


def check(cond, what, detail=""):
    print(("ok   " if cond else "FAIL ") + what + ("" if cond else detail), flush=True)
    if not cond:
        FAILED.append(what)
    return cond


def wait_for(what, fn, timeout=30.0, interval=0.02):
    """Polls fn() until it returns something truthy or the deadline passes."""
    deadline = time.monotonic() + timeout
    while True:
        v = fn()
        if v:
            return v
        if time.monotonic() > deadline:
            raise AssertionError("timed out after %.0f s waiting for %s" % (timeout, what))
        time.sleep(interval)  # polling interval, bounded by the deadline


def run_case(case, scope):
    """Runs scope["case_" + case](), a timed-out wait counting as a failure,
    then prints the verdict and exits 1 if anything failed."""
    try:
        scope["case_" + case]()
    except AssertionError as e:
        FAILED.append(str(e))
        print("FAIL " + str(e), flush=True)
    print("%s: %s" % (case, "FAILED" if FAILED else "passed"), flush=True)
    sys.exit(1 if FAILED else 0)
