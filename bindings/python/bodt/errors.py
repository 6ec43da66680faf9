"""Exceptions for the failed calls of libbodt, one class per bodt_status."""

from .enums import Status
from .results import StepReport

__all__ = [
    "BadMeshError",
    "CancelledError",
    "Error",
    "FileError",
    "InvalidArgumentError",
    "NumericError",
    "OutOfMemoryError",
    "UnsupportedError",
    "WrongStateError",
    "error_for",
]


class Error(Exception):
    """A libbodt call failed.

    ``status`` is the :class:`Status` it returned (a plain int for a code
    this package does not know) and ``message`` the library's message
    (bodt_mesh_last_error), which names the offending entity.
    """

    def __init__(self, status: Status | int, status_text: str, message: str) -> None:
        super().__init__(f"{status_text}: {message}" if message else status_text)
        self.status = status
        self.message = message


class InvalidArgumentError(Error, ValueError):
    """BODT_ERR_INVALID_ARGUMENT: a bad count, key, value or index."""


class BadMeshError(Error):
    """BODT_ERR_BAD_MESH: the mesh data is not a valid mesh."""


class OutOfMemoryError(Error, MemoryError):
    """BODT_ERR_OUT_OF_MEMORY."""


class WrongStateError(Error):
    """BODT_ERR_WRONG_STATE: the call is not valid for this mesh now."""


class NumericError(Error):
    """BODT_ERR_NUMERIC: a computation failed."""


class FileError(Error):
    """BODT_ERR_IO: a file is missing, unreadable or malformed."""


class CancelledError(Error):
    """BODT_ERR_CANCELLED: the improve() callback asked to stop.

    ``reports`` holds the :class:`~bodt.StepReport` of each step that
    improve() call did, as it would have returned them: the mesh keeps these
    steps, the last being the one whose callback stopped the run.
    """

    def __init__(self, status: Status | int, status_text: str, message: str) -> None:
        super().__init__(status, status_text, message)
        self.reports: list[StepReport] = []


class UnsupportedError(Error):
    """BODT_ERR_UNSUPPORTED: a format, mode or feature not built in."""


_CLASSES: dict[Status, type[Error]] = {
    Status.INVALID_ARGUMENT: InvalidArgumentError,
    Status.BAD_MESH: BadMeshError,
    Status.OUT_OF_MEMORY: OutOfMemoryError,
    Status.WRONG_STATE: WrongStateError,
    Status.NUMERIC: NumericError,
    Status.IO: FileError,
    Status.CANCELLED: CancelledError,
    Status.UNSUPPORTED: UnsupportedError,
}


def error_for(status: int, status_text: str, message: str) -> Error:
    """The exception for a failed call: the subclass chosen by ``status``."""
    try:
        known = Status(status)
    except ValueError:
        return Error(status, status_text, message)
    return _CLASSES.get(known, Error)(known, status_text, message)
