"""The package's version, in one place (pyproject.toml reads it; CHANGELOG.md records it)."""

__version__ = "0.3.0"
