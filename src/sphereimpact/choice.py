"""A closed set of named options, written as their words: the base of every enumeration the inputs and tables use."""

from __future__ import annotations

from enum import StrEnum


class Choice(StrEnum):
    """One of a closed set of options; its value is the word that inputs, tables and JSON hold, so a member is
    written as that word wherever it is written."""

    @classmethod
    def parse(cls, value, name: str):
        """The member named ``value`` (a member or its word); ValueError naming ``name`` and the words allowed."""
        try:
            return cls(value)
        except ValueError:
            raise ValueError(f"{name} must be one of {', '.join(cls)}; got {value!r}") from None
