"""Exceptions of tribofe, one class per exit status of the `tribofe` command.

Every error carries the library's message (naming the parameter, file or line and what to
change) and the exit status the command would have returned (`status`).
"""


class TribofeError(Exception):
    """Base class; `status` is the command's exit status for the same failure."""

    status = 1

    def __init__(self, message, status=None):
        super().__init__(message)
        if status is not None:
            self.status = status


class InputError(TribofeError, ValueError):
    """Bad input (exit status 2): a parameter, scene key, mesh or file refused before work."""

    status = 2


class NumericalError(TribofeError, ArithmeticError):
    """Numerical refusal (exit status 3): a singular or ill-conditioned system, a failed self-check."""

    status = 3


class OutputError(TribofeError, OSError):
    """Failure while writing results, or a resource the system refused (exit status 4)."""

    status = 4


class Interrupted(TribofeError, KeyboardInterrupt):
    """The run was cancelled (exit status 130)."""

    status = 130
