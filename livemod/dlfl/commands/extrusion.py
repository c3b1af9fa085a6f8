"""Thesis commands of the extrusion and connection family: extrude, connect*, addHandle."""

from __future__ import annotations

__all__: list[str] = []
