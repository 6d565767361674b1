"""Each argument of the Python entry points checked by kind before anything runs, so that a
mistake is a TypeError or ValueError naming the argument, never a value coerced into another
(int(1.5) is 1, bool("no") is True, list("core") is four letters) or an error from deep inside."""

from numbers import Real
from os import PathLike
from typing import Any


def _kind(value: Any) -> str:
    return f"{value!r} ({type(value).__name__})"


def _unicode(name: str, value: str) -> str:
    """`value`, if it is valid Unicode (no lone surrogate), which is all the native calls take."""
    try:
        value.encode("utf-8")
    except UnicodeEncodeError:
        raise ValueError(f"{name}: expected a string of valid Unicode, got {value!r} (a lone surrogate)") from None
    return value


def count(name: str, value: Any, least: int = 1) -> int:
    """A whole number at least `least`."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"{name}: expected a whole number, got {_kind(value)}")
    if value < least:
        raise ValueError(f"{name}: expected at least {least}, got {value}")
    return value


def flag(name: str, value: Any) -> bool:
    """True or False ('no' is not False)."""
    if not isinstance(value, bool):
        raise TypeError(f"{name}: expected True or False, got {_kind(value)}")
    return value


def number(name: str, value: Any) -> float:
    """A real number (True is not one)."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{name}: expected a number, got {_kind(value)}")
    return float(value)


def optional_number(name: str, value: Any):
    """None, or a real number."""
    return None if value is None else number(name, value)


def numbers(name: str, value: Any) -> list:
    """A sequence of real numbers."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
        raise TypeError(f"{name}: expected a list of numbers, got {_kind(value)}")
    return [number(f"{name}[{i}]", v) for i, v in enumerate(value)]


def text(name: str, value: Any) -> str:
    """A string."""
    if not isinstance(value, str):
        raise TypeError(f"{name}: expected a string, got {_kind(value)}")
    return _unicode(name, value)


def texts(name: str, value: Any) -> list:
    """A sequence of strings; one string is not a list of them (its letters would be taken)."""
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{name}: expected a list of names, got the one string {value!r}: write [{value!r}]")
    if not hasattr(value, "__iter__"):
        raise TypeError(f"{name}: expected a list of names, got {_kind(value)}")
    return [text(f"{name}[{i}]", v) for i, v in enumerate(value)]


def path(name: str, value: Any) -> str:
    """A path, as a string or a PathLike."""
    if not isinstance(value, (str, PathLike)):
        raise TypeError(f"{name}: expected a path, got {_kind(value)}")
    return _unicode(name, str(value))


def paths(name: str, value: Any) -> list:
    """A sequence of paths; one path is not a list of them (its characters would be taken)."""
    if isinstance(value, (str, bytes, PathLike)):
        raise TypeError(f"{name}: expected a list of folders, got the one path {value!r}: write [{value!r}]")
    if not hasattr(value, "__iter__"):
        raise TypeError(f"{name}: expected a list of folders, got {_kind(value)}")
    return [path(f"{name}[{i}]", v) for i, v in enumerate(value)]


def mapping(name: str, value: Any) -> dict:
    """None (nothing), or a mapping."""
    if value is None:
        return {}
    if not hasattr(value, "items"):
        raise TypeError(f"{name}: expected a dict of field paths to values, got {_kind(value)}")
    return dict(value)
