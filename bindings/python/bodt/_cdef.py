"""bodt.h as cffi declarations: :func:`cffi_cdef`.

cffi's ``ffi.cdef()`` parses C declarations but runs no preprocessor, and
``cc -E`` pulls in the C library's own headers, whose GCC extensions
(``__attribute__``, ``__extension__``) cffi refuses.  So the package ships
bodt.h (the build copies include/bodt.h into it) and reads it here as the C
preprocessor would, for what bodt.h uses and nothing more:

- ``#include`` of a standard header is left out (cffi knows ``size_t`` and
  the ``intN_t`` types);
- ``#ifdef``, ``#ifndef``, ``#if`` with ``defined(NAME)``, ``!``, ``&&``,
  ``||`` and parentheses, ``#elif``, ``#else``, ``#endif`` choose the lines
  a C compiler without ``__cplusplus`` and ``__GNUC__`` would see;
- ``#define NAME <integer>`` stays, as cffi takes it (a constant on the
  library object, also usable as an array length); any other object-like
  macro (``BODT_API``) is replaced by its value where it is used.

Anything else (function-like macros, other directives) raises RuntimeError:
a header this reader does not understand fails loudly, never silently.
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
_CONDITION_TOKEN = re.compile(r"\s*(defined\s*\(\s*\w+\s*\)|defined\s+\w+|&&|\|\||!|\(|\))\s*")


def _evaluate(condition: str, macros: dict[str, str]) -> bool:
    """An #if condition made only of defined(NAME), !, &&, || and parentheses."""
    tokens = []
    position = 0
    while position < len(condition):
        token = _CONDITION_TOKEN.match(condition, position)
        if token is None:
            raise RuntimeError(f"bodt.h: cffi_cdef cannot evaluate '#if {condition}'")
        tokens.append(token.group(1))
        position = token.end()
    tokens.append("")  # the end

    # C's precedence: ! binds tighter than &&, && tighter than ||
    def either() -> bool:
        value = both()
        while tokens[0] == "||":
            tokens.pop(0)
            value = both() or value
        return value

    def both() -> bool:
        value = single()
        while tokens[0] == "&&":
            tokens.pop(0)
            value = single() and value
        return value

    def single() -> bool:
        token = tokens.pop(0)
        if token == "!":
            return not single()
        if token == "(":
            value = either()
            if tokens.pop(0) != ")":
                raise RuntimeError(f"bodt.h: unbalanced parentheses in '#if {condition}'")
            return value
        if token.startswith("defined"):
            return re.sub(r"defined|[()\s]", "", token) in macros
        raise RuntimeError(f"bodt.h: cffi_cdef cannot evaluate '#if {condition}'")

    value = either()
    if tokens != [""]:
        raise RuntimeError(f"bodt.h: cffi_cdef cannot evaluate '#if {condition}'")
    return value


def declarations(header: str) -> str:
    """The text of a header as cffi's cdef takes it (see the module's docstring)."""
    text = re.sub(r"/\*.*?\*/", " ", header, flags=re.S)  # comments, which may hold '#'
    text = re.sub(r"//[^\n]*", "", text)
    text = text.replace("\\\n", " ")
    macros: dict[str, str] = {}  # every macro defined so far -> its value
    substitutions: dict[str, str] = {}  # the non-integer ones, replaced where used
    active = [True]  # per open #if: whether its current branch is kept (and all enclosing ones)
    taken = [True]  # per open #if: whether one of its branches was kept already
    lines = []
    for line in text.splitlines():
        directive = _DIRECTIVE.fullmatch(line) if line.lstrip().startswith("#") else None
        if directive is None:
            if active[-1] and line.strip():
                for name, value in substitutions.items():
                    line = re.sub(rf"\b{name}\b" + ("" if value else r"\s*"), value, line)
                lines.append(line.rstrip())
            continue
        name, argument = directive.groups()
        if name in ("if", "ifdef", "ifndef"):
            if name == "if":
                keep = _evaluate(argument, macros)
            else:
                keep = (argument in macros) == (name == "ifdef")
            active.append(active[-1] and keep)
            taken.append(keep)
        elif name in ("elif", "else"):
            if len(active) == 1:
                raise RuntimeError(f"bodt.h: #{name} without #if")
            keep = not taken[-1] and (name == "else" or _evaluate(argument, macros))
            taken[-1] = taken[-1] or keep
            active[-1] = active[-2] and keep
        elif name == "endif":
            if len(active) == 1:
                raise RuntimeError("bodt.h: #endif without #if")
            active.pop()
            taken.pop()
        elif not active[-1]:
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
    if len(active) != 1:
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
