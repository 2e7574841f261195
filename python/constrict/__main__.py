# SPDX-License-Identifier: GPL-3.0-or-later
"""``python3 -m constrict ARGS...`` is ``constrict ARGS...``: the package's own CLI executable
replaces this process with the same arguments, so output files, messages and exit codes are the
CLI's by construction (docs/cli.md)."""
import os
import sys


def main(argv=None) -> None:
    """Execs the packaged CLI with ``argv`` (default: this process's arguments); never returns."""
    from constrict import cli_path

    args = sys.argv[1:] if argv is None else list(argv)
    try:
        exe = cli_path()
    except FileNotFoundError as e:
        sys.exit(f"constrict: error: {e}")
    sys.stdout.flush()
    sys.stderr.flush()
    os.execv(exe, ["constrict", *args])


if __name__ == "__main__":
    main()
