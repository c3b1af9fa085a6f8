"""Freeing a framebuffer with what is attached to it (the renderer's parts, the
window's kept frame). Must be called on the thread that owns the GL context."""

from __future__ import annotations

import moderngl


def release_framebuffer(fbo: moderngl.Framebuffer) -> None:
    """Free ``fbo`` and the textures and renderbuffers attached to it."""
    for attachment in (*fbo.color_attachments, fbo.depth_attachment):
        if attachment is not None:
            attachment.release()
    fbo.release()
