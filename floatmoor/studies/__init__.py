"""The studies behind the validation pages (the quasi-dynamic verification study): internal,
run by the tests and the docs; no public API."""

__all__: list[str] = []
