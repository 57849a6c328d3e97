"""Type hints of the native compiler module (``python/rust/compiler``)."""

def compile(text: str, path: str, **options: object) -> tuple[str, str]:
    """The generated Rust module and the interface JSON of model ``text``;
    raises ``autosim.errors.CompileError`` with the rendered diagnostics."""

def sources() -> list[tuple[str, str]]:
    """The runtime's and the wrapper's sources, ``(relative path, text)``."""

def version() -> tuple[str, str]:
    """The package version and the fingerprint of the compiler's sources."""
