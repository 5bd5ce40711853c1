"""Errors and messages: the two exceptions a plot may raise, the exit
statuses, and the one-line errors and notes on stderr (prefixed with
plot.py, the command users run)."""

import sys


EXIT_PLOT_FAILED = 1
EXIT_BAD_DIR = 2


class InputError(Exception):
    """An input file exists but its contents cannot be plotted."""


class SkipPlot(Exception):
    """An optional input of a plot (a field, the h5py module) is missing: the
    plot is skipped with a note, which is not an error."""


def fail(message: str) -> None:
    """Print a one-line error and exit 2 (the documented bad-input status)."""
    print(f"plot.py: error: {message}", file=sys.stderr)
    sys.exit(EXIT_BAD_DIR)


def note(message: str) -> None:
    """A one-line remark on stderr: an optional input is missing and what is
    drawn instead.  Not an error (the exit status is unchanged)."""
    print(f"plot.py: note: {message}", file=sys.stderr)
