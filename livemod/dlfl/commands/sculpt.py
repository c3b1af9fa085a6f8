"""Thesis commands of the sculpting family: rind, wireframe, column and extras."""

from __future__ import annotations

__all__: list[str] = []
