"""bodt.h as cffi declarations: :func:`cffi_cdef`.

cffi's ``ffi.cdef()`` parses C declarations but runs no preprocessor, and
``cc -E`` pulls in the C library's own headers, whose GCC extensions
(``__attribute__``, ``__extension__``) cffi refuses.  So the package ships
bodt.h (the build copies include/bodt.h into it) and reads it here as the C
preprocessor would, for what bodt.h uses and nothing more:

- ``#include`` of a standard header is left out (cffi knows ``size_t`` and
  the ``intN_t`` types);
- ``#ifdef``, ``#ifndef``, ``#if defined(A) && defined(B) ...``, ``#else``
  and ``#endif`` choose the lines a C compiler sees that defines none of
  the macros bodt.h tests but bodt.h's own (no ``__cplusplus``,
  ``__GNUC__`` or ``BODT_BUILDING_LIBRARY``);
- ``#define NAME <integer>`` stays, as cffi takes it (a constant on the
  library object, also usable as an array length); any other object-like
  macro (``BODT_API``) is replaced by its value where it is used.

Anything else (``#elif``, other #if conditions, function-like macros, other
directives) raises RuntimeError: a header this reader does not understand
fails loudly, never silently.  tests/test_cffi_header.py checks the result
against what the C preprocessor gives.
"""

import functools
import os
import re

__all__ = ["HEADER", "cffi_cdef"]

#: bodt.h as shipped in the package.
HEADER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bodt.h")

# The standard headers cffi needs no declarations from.
_KNOWN_INCLUDES = {"<stddef.h>", "<stdint.h>"}
_INTEGER = re.compile(r"\(?\s*(-?\s*(?:0[xX][0-9a-fA-F]+|\d+))\s*\)?")
_DIRECTIVE = re.compile(r"\s*#\s*(\w+)\s*(.*?)\s*")
_ALL_DEFINED = re.compile(r"defined\s*\(\s*\w+\s*\)(\s*&&\s*defined\s*\(\s*\w+\s*\))*")


def _condition(directive: str, argument: str, macros: dict[str, str]) -> bool:
    """An #if's, #ifdef's or #ifndef's condition, no macro being defined but the header's own (``macros``).

    An #if may only test that names are all defined, as bodt.h's one #if
    does (``defined(BODT_BUILDING_LIBRARY) && defined(__GNUC__)``, which
    picks BODT_API's value): a reader of more would be code that bodt.h
    never runs.
    """
    if directive == "ifdef":
        return argument in macros
    if directive == "ifndef":
        return argument not in macros
    if not _ALL_DEFINED.fullmatch(argument):
        raise RuntimeError(f"bodt.h: cffi_cdef cannot evaluate '#if {argument}'")
    return all(name in macros for name in re.findall(r"(\w+)\s*\)", argument))


def declarations(header: str) -> str:
    """The text of a header as cffi's cdef takes it (see the module's docstring)."""
    text = re.sub(r"/\*.*?\*/", " ", header, flags=re.S)  # comments, which may hold '#'
    text = re.sub(r"//[^\n]*", "", text)
    text = text.replace("\\\n", " ")
    macros: dict[str, str] = {}  # every macro defined so far -> its value
    substitutions: dict[str, str] = {}  # the non-integer ones, replaced where used
    kept = True  # whether the lines here are kept
    open_ifs: list[tuple[bool, bool]] = []  # per open #if: (whether the lines around it are kept, its condition)
    lines = []
    for line in text.splitlines():
        directive = _DIRECTIVE.fullmatch(line) if line.lstrip().startswith("#") else None
        if directive is None:
            if kept and line.strip():
                for name, value in substitutions.items():
                    line = re.sub(rf"\b{name}\b" + ("" if value else r"\s*"), value, line)
                lines.append(line.rstrip())
            continue
        name, argument = directive.groups()
        if name in ("if", "ifdef", "ifndef"):
            condition = _condition(name, argument, macros)
            open_ifs.append((kept, condition))
            kept = kept and condition
        elif name in ("else", "endif"):
            if not open_ifs:
                raise RuntimeError(f"bodt.h: #{name} without #if")
            around, condition = open_ifs[-1]
            if name == "else":
                kept = around and not condition
            else:
                kept = around
                open_ifs.pop()
        elif name == "elif":  # even in lines left out: it would decide which lines follow
            raise RuntimeError(f"bodt.h: cffi_cdef does not handle '#elif {argument}'")
        elif not kept:
            continue
        elif name == "include" and argument in _KNOWN_INCLUDES:
            continue
        elif name == "define" and re.fullmatch(r"\w+(\s.*)?", argument):
            macro, _, value = argument.partition(" ")
            value = value.strip()
            macros[macro] = value
            integer = _INTEGER.fullmatch(value)
            if integer:
                lines.append(f"#define {macro} {integer.group(1).replace(' ', '')}")
            else:
                substitutions[macro] = value
        else:
            raise RuntimeError(f"bodt.h: cffi_cdef does not handle '#{name} {argument}'")
    if open_ifs:
        raise RuntimeError("bodt.h: #if without #endif")
    return "\n".join(lines) + "\n"


@functools.cache
def cffi_cdef() -> str:
    """bodt.h's declarations for ``cffi.FFI().cdef()``: types, enums, functions and integer #defines.

    Read from the bodt.h shipped in this package, the header of the library
    the package loads::

        ffi = cffi.FFI()
        ffi.cdef(bodt.cffi_cdef())
        lib = ffi.dlopen(bodt.library_path())
    """
    with open(HEADER, encoding="utf-8") as f:
        return declarations(f.read())
