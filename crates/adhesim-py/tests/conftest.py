"""Fixtures shared by the tests of the package."""

import signal

import pytest


@pytest.fixture
def sigint_raises_keyboard_interrupt():
    """Python turns SIGINT into KeyboardInterrupt only if its parent did not ignore the
    signal (a CI runner may start it with SIGINT ignored): install the default handler,
    as an interactive session has it, for the test's duration."""
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
def resident_kib():
    """A function giving the resident set size of this process in KiB (Linux)."""
    return _resident_kib
