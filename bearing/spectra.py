"""Envelope spectrum (kept for existing imports): the functions live in
:mod:`.diagnostics.envelope`."""
from .diagnostics.envelope import envelope, envelope_spectrum

__all__ = ["envelope", "envelope_spectrum"]
