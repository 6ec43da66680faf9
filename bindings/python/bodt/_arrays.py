"""Arguments for the C calls: checks, conversions to C types, pointers.

Every array handed to C is C-contiguous with the C element type and the
length the call will read, checked here: a wrong shape raises ValueError,
never an out-of-bounds read.
"""

import ctypes
import operator

import numpy as np
from numpy.typing import ArrayLike, DTypeLike

__all__ = ["INT_DTYPES", "checked_int_dtype", "float_array", "index_array", "int32", "pointer"]

#: The dtypes a Mesh may give its integer arrays in (its ``int_dtype``).
INT_DTYPES = (np.dtype(np.int64), np.dtype(np.int32))

_INT32 = np.iinfo(np.int32)


def int32(value: int, name: str) -> int:
    """``value`` checked to be an integer that fits the C API's int32_t (ctypes would wrap it silently)."""
    try:
        n = operator.index(value)
    except TypeError:
        raise TypeError(f"{name} must be an integer, got {value!r}") from None
    if not _INT32.min <= n <= _INT32.max:
        raise ValueError(f"{name} = {n} is outside the int32 range of libbodt")
    return n


def _check_shape(array: np.ndarray, shape: tuple[int | None, ...], name: str) -> None:
    wanted = "(" + ", ".join("n" if n is None else str(n) for n in shape) + (",)" if len(shape) == 1 else ")")
    if array.ndim != len(shape) or any(n is not None and n != got for n, got in zip(shape, array.shape)):
        raise ValueError(f"{name} must have shape {wanted}, got {array.shape}")


def float_array(values: ArrayLike, shape: tuple[int | None, ...], name: str) -> np.ndarray:
    """``values`` as a C-contiguous float64 array of ``shape`` (None: any length)."""
    array = np.ascontiguousarray(values, dtype=np.float64)
    _check_shape(array, shape, name)
    return array


def index_array(values: ArrayLike, shape: tuple[int | None, ...], name: str) -> np.ndarray:
    """``values`` as a C-contiguous int32 array of ``shape`` (None: any length).

    Any integer dtype is taken if its values fit in int32; other dtypes
    (floats, which would be truncated) raise TypeError.  An empty sequence
    (``[]``) is taken as no rows of any fixed ``shape``.
    """
    array = np.asarray(values)
    if array.size == 0:
        array = array.astype(np.int32)
        if array.ndim == 1 and None not in shape[1:]:
            array = array.reshape((0, *shape[1:]))
    elif array.dtype.kind not in "iu":
        raise TypeError(f"{name} must hold integers, got dtype {array.dtype}")
    elif not np.can_cast(array.dtype, np.int32):
        outside = np.flatnonzero((array < _INT32.min) | (array > _INT32.max))
        if outside.size:
            at = np.unravel_index(outside[0], array.shape)
            raise ValueError(
                f"{name} holds {array[at]} at {list(map(int, at))}, outside the int32 range of libbodt "
                f"[{_INT32.min}, {_INT32.max}] ({outside.size} such values)"
            )
    _check_shape(array, shape, name)
    return np.ascontiguousarray(array, dtype=np.int32)


def checked_int_dtype(value: DTypeLike) -> np.dtype:
    """``value`` checked to be one of INT_DTYPES."""
    dtype = np.dtype(value)
    if dtype not in INT_DTYPES:
        raise ValueError(f"int_dtype must be numpy.int64 or numpy.int32, got {dtype}")
    return dtype


def pointer(array: np.ndarray | None) -> "ctypes._Pointer | None":
    """The address of a C-contiguous array's data, or None (NULL)."""
    if array is None:
        return None
    assert array.flags.c_contiguous
    return array.ctypes.data_as(ctypes.POINTER(np.ctypeslib.as_ctypes_type(array.dtype)))
