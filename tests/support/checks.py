"""What the Python tests that CTest runs share (tests/cli, tests/interop):
checks that record a failure and let the test go on, the exit status they
add up to, and running a program for its exit status and output.
"""
import subprocess

FAILURES = []


def check(cond, what):
    """`cond`; when false, `what` is recorded as a failure and printed."""
    if not cond:
        FAILURES.append(what)
        print("FAIL:", what)
    return cond


def exit_status(passed="ok"):
    """1 when a check failed (saying how many), else 0 (printing `passed`)."""
    if FAILURES:
        print("%d check(s) failed" % len(FAILURES))
        return 1
    print(passed)
    return 0


def run(program, *args, timeout=60):
    """Runs the program with args: (exit status, stdout, stderr) as text."""
    p = subprocess.run([program] + list(args), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       universal_newlines=True, timeout=timeout)
    return p.returncode, p.stdout, p.stderr
