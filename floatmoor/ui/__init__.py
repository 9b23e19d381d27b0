"""Terminal progress of the command line: internal, no public API."""

__all__: list[str] = []
