"""Fixtures shared by the tests of the package."""

import signal

import pytest


@pytest.fixture
def sigint_raises_keyboard_interrupt():
    """Python turns SIGINT into KeyboardInterrupt only if its parent did not ignore the
    signal (a CI runner may start it with SIGINT ignored): install the default handler,
    as an interactive interpreter has it, for the test's duration."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def _resident_kib():
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    raise RuntimeError("no VmRSS in /proc/self/status")


@pytest.fixture
def resident_growth_kib():
    """A function `growth(call, warm_up, repeats)`: calls `call()` `warm_up` times, then
    `repeats` times, and gives how much the resident set size (KiB, Linux) grew over the
    repeats."""

    def growth(call, warm_up, repeats):
        for _ in range(warm_up):
            call()
        before = _resident_kib()
        for _ in range(repeats):
            call()
        return _resident_kib() - before

    return growth
