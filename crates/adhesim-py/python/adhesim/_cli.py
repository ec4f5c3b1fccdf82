"""The ``adhesim`` console script of the wheel: the command line of the native binary.

``pip install`` puts ``adhesim`` in the environment's bin folder; it runs the same Rust
code as ``cargo run --release --`` (``adhesim_cli::main_with_args``), with the same
output and exit codes (0 success, 1 error, 2 usage error).
"""

import signal
import sys

from ._adhesim import cli_main


def main() -> None:
    """Runs ``adhesim`` with this process's arguments and exits with its code."""
    # Python turns Ctrl-C into KeyboardInterrupt at its next bytecode, which a long Rust
    # run never reaches: restore the default, so that Ctrl-C stops the run as it stops
    # the native binary. (SIGPIPE is ignored by both, so a closed pipe is an error the
    # command handles itself.)
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    sys.exit(cli_main(["adhesim", *sys.argv[1:]]))


if __name__ == "__main__":
    main()
