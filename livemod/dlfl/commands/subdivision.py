"""Thesis commands of the remeshing family: subdivide, subdivideFace(s), dual."""

from __future__ import annotations

__all__: list[str] = []
