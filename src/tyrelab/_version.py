"""The version of tyrelab, in one place (read by pyproject.toml and ``tyrelab.__version__``)."""

__version__ = "0.1.0"
