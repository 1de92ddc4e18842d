"""A registry of definitions by name (the contact laws, the tangential models): :meth:`Registry.register` adds
one, :meth:`Registry.named` looks one up; nothing else needs to change for a new definition."""

from __future__ import annotations


class Registry(dict):
    """Name -> definition of one kind.

    Parameters
    ----------
    kind : type
        What a definition is (``ContactLaw``, ``TangentialModel``); anything else is refused.
    noun : str
        What messages call one (``law``, ``tangential model``).
    field : str
        The Scene field that names one (``model``, ``tangential``), for the lookup's message.
    """

    def __init__(self, kind: type, noun: str, field: str):
        super().__init__()
        self.kind, self.noun, self.field = kind, noun, field

    def register(self, item):
        """Add ``item`` under its name (``ValueError`` if the name is taken by another definition)."""
        if not isinstance(item, self.kind):
            raise TypeError(f"{self.noun.split()[-1]} must be a {self.kind.__name__}; got {type(item).__name__}")
        if item.name in self and self[item.name] is not item:
            raise ValueError(f"a {self.noun} named {item.name!r} is already registered")
        self[item.name] = item
        return item

    def named(self, name: str):
        """The definition ``name``; ``ValueError`` listing the registered ones otherwise."""
        try:
            return self[name]
        except (KeyError, TypeError):
            raise ValueError(f"{self.field} must be one of {', '.join(self)}; got {name!r}") from None
