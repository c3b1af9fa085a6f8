"""The section's GL side: the clip plane, and the cap that closes a cut mesh.

:class:`SectionCap` owns the clip plane of the mesh programs (set while a pass is
drawn inside :meth:`SectionCap.cut`), the cap program's view and hatch, the
winding target the cap pass counts into, and the full-screen vertex array of the
cap pass. The plane itself is ``Style.section``; the window moves it through
:class:`~livemod.viewer.section.SectionPlane`. Every method must be called on the
thread that owns the GL context.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Iterator, Mapping

import moderngl
import numpy as np

from .camera import Camera
from .framebuffers import release_framebuffer
from .uploads import MeshGPU, SurfaceGPU

GL_CLIP_DISTANCE0 = 0x3000  # moderngl has no name for it: enable_direct takes the GL enum
NO_CUT = (0.0, 0.0, 0.0, 1.0)  # a clip plane every point is in front of


def hatch_spacing(pixel_size: float, facing: float, pixels: float = 8.0) -> float:
    """World distance between the section cap's hatch lines.

    Args:
        pixel_size: world size of a pixel at the camera's target.
        facing: |cosine| between the line of sight and the plane's normal; a plane
            seen aslant squeezes the lines together, so they are spread by 1/facing
            (by at most 4x).
        pixels: the wanted gap in pixels on a plane seen face on.

    Returns:
        a power of two near ``pixels * pixel_size / facing``, so that the lines stay
        put while the view turns or zooms a little (they halve or double in number
        at a step).
    """
    wanted = pixels * pixel_size / max(facing, 0.25)
    return float(2.0 ** np.round(np.log2(wanted)))


class SectionCap:
    """Cuts the mesh passes at the section's plane and caps what they cut open.

    Args:
        ctx: the GL context.
        programs: the renderer's programs by name; each with a ``clip_plane``
            uniform takes the clip plane, "cap" draws the cap.
    """

    def __init__(self, ctx: moderngl.Context, programs: Mapping[str, moderngl.Program]) -> None:
        self.ctx = ctx
        self.clipped = [program for program in programs.values() if "clip_plane" in program]
        self.program = programs["cap"]
        self.vao = ctx.vertex_array(self.program, [])  # three vertices the shader places
        self.winding: tuple[moderngl.Framebuffer, moderngl.Texture] | None = None
        self._set_clip_plane(NO_CUT)

    @contextlib.contextmanager
    def cut(self, section: tuple[int, float] | None) -> Iterator[None]:
        """Clip the mesh passes drawn inside at ``section`` (see ``Style.section``)."""
        if section is None:
            yield
            return
        axis, at = section
        plane = [0.0, 0.0, 0.0, float(at)]
        plane[axis] = -1.0  # distance at - p[axis]: negative beyond the plane
        self._set_clip_plane(tuple(plane))
        self.ctx.enable_direct(GL_CLIP_DISTANCE0)
        try:
            yield
        finally:
            self.ctx.disable_direct(GL_CLIP_DISTANCE0)
            # llvmpipe clips by a written gl_ClipDistance even when the distance is
            # disabled: the plane itself must go back to one that keeps everything
            self._set_clip_plane(NO_CUT)

    def _set_clip_plane(self, plane: tuple[float, ...]) -> None:
        for program in self.clipped:
            program["clip_plane"].value = plane  # type: ignore[union-attr]

    def set_view(self, camera: Camera, aspect: float, height: int,
                 section: tuple[int, float] | None) -> None:
        """What the cap pass needs to turn each pixel back into a line of sight, and
        the hatch of the ``section``'s plane as ``camera`` sees it on a target of
        ``aspect`` (width / height) and ``height`` pixels."""
        cap = self.program
        cap["eye"].value = tuple(float(v) for v in camera.eye())  # type: ignore[union-attr]
        basis = camera.basis()
        # a row-major (3, 3) of rows right, up, back is the column-major matrix of columns
        cap["camera_basis"].write(basis.astype(np.float32).tobytes())  # type: ignore[union-attr]
        half = camera.half_height() if camera.ortho else math.tan(math.radians(camera.fov) / 2)
        cap["half_size"].value = (half * aspect, half)  # type: ignore[union-attr]
        cap["ortho"].value = int(camera.ortho)  # type: ignore[union-attr]
        if section is None:
            return
        axis = section[0]
        along = [1.0, 1.0, 1.0]  # hatch at 45 degrees to the two axes in the plane
        along[axis] = 0.0
        cap["hatch_axis"].value = tuple(along)  # type: ignore[union-attr]
        pixel_size = 2.0 * camera.half_height() / max(height, 1)
        cap["hatch_spacing"].value = hatch_spacing(  # type: ignore[union-attr]
            pixel_size, abs(float(basis[2][axis])))

    def draw(self, mesh: MeshGPU | SurfaceGPU, color: tuple[float, float, float],
             current: bool = True) -> None:
        """The section's cap of a cut closed mesh, in a darker ``color``: the mesh's
        cut triangles count the winding of each pixel into an image, then one pass
        over the viewport draws the plane where it is not 0
        (``shaders.CAP_FRAGMENT``), at its own depth. Must follow the mesh's face
        pass, into the framebuffer now in use; of a preview's surface, caps its
        part of the ``current`` object (or of the others)."""
        target, viewport = self.ctx.fbo, self.ctx.viewport
        winding = self._count_winding(mesh, (viewport[2], viewport[3]), current)
        target.use()
        self.ctx.viewport = viewport
        self.ctx.enable(moderngl.DEPTH_TEST)
        program = self.program
        program["viewport"].value = tuple(float(v) for v in viewport[2:])  # type: ignore[union-attr]
        program["cap_color"].value = tuple(0.72 * c for c in color)  # type: ignore[union-attr]
        winding.use(6)
        self.vao.render(moderngl.TRIANGLES, vertices=3)

    def _count_winding(self, mesh: MeshGPU | SurfaceGPU, size: tuple[int, int],
                       current: bool = True) -> moderngl.Texture:
        """Draw the cut triangles of ``mesh`` into the winding image of ``size``, front
        faces adding 1 and back faces taking 1 away, and return the image. Leaves
        the winding target bound and the depth test and culling off."""
        target, image = self._winding_target(size)
        target.use()
        target.clear(0.0, 0.0, 0.0, 0.0)
        self.ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        self.ctx.enable(moderngl.BLEND)
        self.ctx.blend_func = moderngl.ONE, moderngl.ONE
        if isinstance(mesh, SurfaceGPU):  # the part of the object capped only
            first, count = mesh.part(current)
            mesh.winding_vao.render(moderngl.TRIANGLES, vertices=3 * count, first=3 * first)
        else:
            mesh.winding_vao.render(moderngl.TRIANGLES)
        self.ctx.disable(moderngl.BLEND)  # the text pass sets its own blend function
        return image

    def _winding_target(self, size: tuple[int, int],
                        ) -> tuple[moderngl.Framebuffer, moderngl.Texture]:
        """A one-channel float framebuffer of ``size`` and its texture, for the cap's
        winding pass (kept for the next frame of that size)."""
        if self.winding is not None and self.winding[0].size == size:
            return self.winding
        if self.winding is not None:
            release_framebuffer(self.winding[0])
        texture = self.ctx.texture(size, 1, dtype="f2")
        texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
        self.winding = (self.ctx.framebuffer([texture]), texture)
        return self.winding

    def release(self) -> None:
        """Free the winding target and the cap's vertex array (before the programs,
        which the renderer frees)."""
        if self.winding is not None:
            release_framebuffer(self.winding[0])
            self.winding = None
        self.vao.release()
