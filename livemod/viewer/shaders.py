"""GLSL sources of the renderer's passes (GL 3.3 core).

Faces, edges and points write two outputs: the colour, and at location 1 a pick id
(kind << 28 | dense index + 1, see :mod:`livemod.viewer.geometry`). Element indices
come from ``gl_VertexID`` (the flat faces' pulled corners, the points) or
``gl_PrimitiveID`` (edges, smooth faces); per-element data (the face of each
triangle, selection flags) is read from integer textures with ``texelFetch``. A
pass that leaves a part out (the face pass without its wire, the edges with none
selected) uses a variant of its source compiled without that part (:func:`variant`).
"""

# Tables are 1 << TABLE_SHIFT texels wide (or one row of fewer, where the same
# shift and mask give the same texel): shifts, as integer division and modulo by a
# width read from the texture are emulated a lane at a time on software GL (they
# made the face pass several times slower on llvmpipe).
TABLE_SHIFT = 12
FETCH = f"""
ivec2 table_texel(int i) {{
    return ivec2(i & {(1 << TABLE_SHIFT) - 1}, i >> {TABLE_SHIFT});
}}""" + """
uint fetch(usampler2D table, int i) {
    return texelFetch(table, table_texel(i), 0).r;
}
"""


def variant(source: str, *defines: str) -> str:
    """``source`` with ``#define NAME 1`` for each of ``defines`` after its
    ``#version`` line. Software GL runs both sides of a branch on a uniform (a
    lane mask, not a jump), so a pass that never takes a side is compiled
    without it."""
    version, rest = source.lstrip().split("\n", 1)
    return "\n".join([version, *(f"#define {name} 1" for name in defines), rest])


# what a lit surface's fragment shader takes and gives
LIT = """
uniform vec3 base_color;
uniform vec3 back_color;
in vec3 v_normal;
in vec3 v_view;
layout(location = 0) out vec4 color;
layout(location = 1) out uint pick;
"""

# The faces' own colours (the colour mode). The scene's other objects show theirs
# muted as the modelling colour is muted for them: MUTE of the way to a light grey.
MUTE = 0.6
OWN_COLOR = """
uniform float mute;  // 0: the current object's colours; MUTE: the other objects'
vec3 own_color(vec3 rgb) {
    return mix(rgb, vec3(0.77), mute);
}
"""

SHADE = """
vec3 shade(vec3 n, vec3 base) {
    // TopMod's warm/cool model with a key light fixed to the camera (up left),
    // plus a weak fill from the lower right so no side goes flat black.
    vec3 key = normalize(vec3(-0.45, 0.55, 0.7));
    vec3 fill = normalize(vec3(0.6, -0.3, 0.75));
    float cf = pow((1.0 + dot(key, n)) * 0.5, 2.0);
    vec3 lit = mix(vec3(0.11, 0.10, 0.09), vec3(1.0, 0.98, 0.89), cf);
    lit += 0.18 * max(dot(fill, n), 0.0);
    return clamp(0.75 * lit * base + 0.25 * base * 0.55, 0.0, 1.0);
}
vec3 facing_normal(vec3 view_point, vec3 normal) {
    // the interpolated normal, turned to the side the flat normal (from the
    // screen-space derivatives) shows: toward the viewer on front faces
    vec3 flat_normal = normalize(cross(dFdx(view_point), dFdy(view_point)));
    if (dot(normal, normal) <= 0.0) return flat_normal;
    vec3 s = normalize(normal);
    return dot(s, flat_normal) < 0.0 ? -s : s;
}
"""

MESH_VERTEX = """
#version 330
uniform mat4 mvp;
uniform mat4 view;
in vec3 in_position;
out vec3 v_view;
flat out int v_vertex;
uniform float point_size;
in vec3 in_normal;  // bound for smooth shading only (0 otherwise)
out vec3 v_normal;
// the section plane: points where this is negative are cut away (GL_CLIP_DISTANCE0,
// enabled only while a section is drawn)
uniform vec4 clip_plane;
#ifdef COLORS
// a surface whose points carry their face's colour (the coloured preview)
in vec4 in_color;
flat out vec4 v_color;
#endif
void main() {
#ifdef COLORS
    v_color = in_color;
#endif
    gl_ClipDistance[0] = dot(vec4(in_position, 1.0), clip_plane);
    v_view = (view * vec4(in_position, 1.0)).xyz;
    v_normal = mat3(view) * in_normal;
    v_vertex = gl_VertexID;
    gl_PointSize = point_size;
    gl_Position = mvp * vec4(in_position, 1.0);
}
"""

FACE_VERTEX = """
#version 330
// The flat face pass pulls its vertices: it draws three a triangle with no
// attributes, and each reads its corner's vertex and its triangle's entry of
// triangle_face from the tables. Each triangle so has corners of its own, which
// give the fragments their triangle's entry (flat: no gl_PrimitiveID, which costs
// software GL a pass that copies the vertices of every primitive) and the screen
// distances to its sides that are edges (v_sides).
uniform mat4 mvp;
uniform mat4 view;
uniform vec4 clip_plane;  // (see MESH_VERTEX)
uniform usampler2D triangle_face;
uniform usampler2D triangle_index;
uniform sampler2D position_table;
out vec3 v_view;
out vec3 v_normal;
flat out uint v_entry;
// per side (v1v2, v2v0, v0v1) the coordinate of the corner across from it: 0 along
// the side, 1 at that corner; 1 throughout for a fan's diagonal, which is no edge
noperspective out vec3 v_sides;
""" + FETCH + """
void main() {
    int primitive = gl_VertexID / 3;
    int corner = gl_VertexID - 3 * primitive;
    uint vertex = fetch(triangle_index, gl_VertexID);
    vec3 p = texelFetch(position_table, table_texel(int(vertex)), 0).xyz;
    v_entry = fetch(triangle_face, primitive);
    uint sides = v_entry >> 29;
    vec3 own = vec3(corner == 0, corner == 1, corner == 2);
    v_sides = mix(vec3(1.0), own, bvec3((sides & 2u) != 0u, (sides & 4u) != 0u,
                                        (sides & 1u) != 0u));
    gl_ClipDistance[0] = dot(vec4(p, 1.0), clip_plane);
    v_view = (view * vec4(p, 1.0)).xyz;
    v_normal = vec3(0.0);
    gl_Position = mvp * vec4(p, 1.0);
}
"""

FACE_FRAGMENT = """
#version 330
uniform usampler2D face_flags;
uniform usampler2D face_colors;  // RGBA8 packed per face, alpha 0: no colour of its own
uniform int use_face_colors;  // 1: draw the faces' own colours (the colour mode)
uniform int pickable;  // 0: the scene's other objects, which hide but are not picked
uniform vec3 selected_color;
uniform vec3 edge_color;
""" + LIT + FETCH + SHADE + OWN_COLOR + """
#ifdef SMOOTH
// smooth shading: shared corners with normals (MESH_VERTEX), the triangle found by
// gl_PrimitiveID and its sides by projecting its corners
uniform usampler2D triangle_face;
uniform usampler2D triangle_index;
uniform sampler2D position_table;
uniform mat4 mvp;
uniform vec2 viewport;
uniform int primitive_base;  // the first triangle drawn (a frame may draw a range)
uint triangle_entry() {
    return fetch(triangle_face, primitive_base + gl_PrimitiveID);
}
vec3 lit_normal() {
    return facing_normal(v_view, v_normal);
}
vec2 screen_of_vertex(int i) {
    uint v = fetch(triangle_index, i);
    vec3 p = texelFetch(position_table, table_texel(int(v)), 0).xyz;
    vec4 clip = mvp * vec4(p, 1.0);
    return (clip.xy / max(clip.w, 1e-9) * 0.5 + 0.5) * viewport;
}
float segment_distance(vec2 p, vec2 a, vec2 b) {
    vec2 ab = b - a;
    float t = clamp(dot(p - a, ab) / max(dot(ab, ab), 1e-12), 0.0, 1.0);
    return length(p - a - t * ab);
}
float side_distance(uint sides) {
    // distance in pixels to the triangle's real sides (fan diagonals are skipped)
    int primitive = primitive_base + gl_PrimitiveID;
    vec2 s0 = screen_of_vertex(3 * primitive);
    vec2 s1 = screen_of_vertex(3 * primitive + 1);
    vec2 s2 = screen_of_vertex(3 * primitive + 2);
    float d = 1e9;
    if ((sides & 1u) != 0u) d = min(d, segment_distance(gl_FragCoord.xy, s0, s1));
    if ((sides & 2u) != 0u) d = min(d, segment_distance(gl_FragCoord.xy, s1, s2));
    if ((sides & 4u) != 0u) d = min(d, segment_distance(gl_FragCoord.xy, s2, s0));
    return d;
}
#else
// flat: the pulled corners of FACE_VERTEX
flat in uint v_entry;
noperspective in vec3 v_sides;
uint triangle_entry() {
    return v_entry;
}
vec3 lit_normal() {
    return facing_normal(v_view, vec3(0.0));
}
float side_distance(uint sides) {
    // distance in pixels to the nearest side that is an edge: its corner's
    // coordinate over that coordinate's screen gradient
    vec3 dx = dFdx(v_sides), dy = dFdy(v_sides);
    vec3 d = v_sides / max(sqrt(dx * dx + dy * dy), vec3(1e-9));
    return min(d.x, min(d.y, d.z));
}
#endif
void main() {
    uint entry = triangle_entry();
    uint face = entry & 0x1FFFFFFFu;
    vec3 n = lit_normal();
    bool selected = fetch(face_flags, int(face)) != 0u;
    vec3 front = base_color;
    if (use_face_colors != 0) {
        uint rgba = fetch(face_colors, int(face));
        if ((rgba >> 24) != 0u) {
            front = own_color(vec3(rgba & 255u, (rgba >> 8) & 255u, (rgba >> 16) & 255u)
                              / 255.0);
        }
    }
    vec3 base = selected ? selected_color : (gl_FrontFacing ? front : back_color);
    vec3 rgb = shade(n, base);
#ifdef WIRE
    rgb = mix(rgb, edge_color, 1.0 - smoothstep(0.35, 0.95, side_distance(entry >> 29)));
#endif
    color = vec4(rgb, 1.0);
    pick = pickable != 0 ? (1u << 28) | (face + 1u) : 0u;
}
"""

SURFACE_FRAGMENT = """
#version 330
// A smooth surface with normals of its own (the patch preview): lit per pixel
// from its interpolated normals; it is never picked. QUICK (the quick picture of
// a moving view): the normal turned by the side seen, not by the flat normal
// from the derivatives (it differs only where the interpolated normal looks
// away from the eye, at the outline). COLORS: its points carry their face's
// colour (alpha 0: none, the base colour), drawn in the colour mode.
""" + LIT + SHADE + """
#ifdef COLORS
""" + OWN_COLOR + """
flat in vec4 v_color;
#endif
void main() {
#ifdef QUICK
    vec3 n = normalize(v_normal);
    n = gl_FrontFacing ? n : -n;
#else
    vec3 n = facing_normal(v_view, v_normal);
#endif
    vec3 front = base_color;
#ifdef COLORS
    if (v_color.a > 0.5) front = own_color(v_color.rgb);
#endif
    color = vec4(shade(n, gl_FrontFacing ? front : back_color), 1.0);
    pick = 0u;
}
"""

WINDING_FRAGMENT = """
#version 330
// Drawn with additive blending and no depth test into a float image: a front face
// adds 1 and a back face takes 1 away, so each pixel ends with the winding number
// of the cut surface along its line of sight (0 outside the solid).
layout(location = 0) out vec4 winding;
void main() {
    winding = vec4(gl_FrontFacing ? 1.0 : -1.0);
}
"""

CAP_VERTEX = """
#version 330
// one triangle over the whole viewport
void main() {
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(p, 0.0, 1.0);
}
"""

CAP_FRAGMENT = """
#version 330
// The section's cap. The line of sight through a pixel crosses the section plane
// inside a closed mesh exactly when the cut surface winds around it: the winding
// pass counts its front faces less its back faces over the pixel, which is +-1 (or
// more where parts of the mesh overlap) inside and 0 outside, whichever side of the
// plane the eye is on. There the cap is drawn, flat and hatched, at the depth of the
// plane, so that it hides what lies behind it as a real cut face would.
uniform sampler2D winding;
uniform mat4 mvp;
uniform vec3 eye;
uniform mat3 camera_basis;  // columns: the camera's right, up and back in the world
uniform vec2 half_size;     // of the view at distance 1 (perspective) or anywhere (ortho)
uniform int ortho;
uniform vec2 viewport;
uniform vec4 clip_plane;
uniform vec3 cap_color;
uniform vec3 hatch_axis;    // lies in the plane: the hatch lines are its level sets
uniform float hatch_spacing;
layout(location = 0) out vec4 color;
layout(location = 1) out uint pick;
void main() {
    vec2 ndc = gl_FragCoord.xy / viewport * 2.0 - 1.0;
    // the line of sight through the pixel, from the camera's own frame (inverting
    // the projection matrix in single precision makes it jitter from pixel to pixel)
    vec3 across = camera_basis * vec3(ndc * half_size, 0.0);
    vec3 forward = -camera_basis[2];
    vec3 origin = ortho != 0 ? eye + across : eye;
    vec3 ray = ortho != 0 ? forward : across + forward;
    float along = dot(clip_plane.xyz, ray);
    float t = -dot(vec4(origin, 1.0), clip_plane) / (along == 0.0 ? 1.0 : along);
    vec3 q = origin + t * ray;
    // derivatives before any discard: they need the neighbouring pixels
    float s = dot(q, hatch_axis) / hatch_spacing;
    float w = max(fwidth(s), 1e-6);
    float off = abs(fract(s + 0.5) - 0.5) / w;  // pixels to the nearest hatch line
    // lines about 1.5 pixels wide, faded out where they would crowd closer than 3 pixels
    float line = (1.0 - smoothstep(0.4, 1.2, off)) * (1.0 - smoothstep(0.25, 0.45, w));
    bool inside = abs(texelFetch(winding, ivec2(gl_FragCoord.xy), 0).r) > 0.5;
    // outside the section, the plane seen edge-on, or behind the eye
    if (!inside || along == 0.0 || (ortho == 0 && t <= 0.0)) discard;
    vec4 clip = mvp * vec4(q, 1.0);
    gl_FragDepth = clamp(0.5 * (gl_DepthRange.diff * clip.z / clip.w + gl_DepthRange.near
                                + gl_DepthRange.far), 0.0, 1.0);
    color = vec4(mix(cap_color, 0.55 * cap_color, line), 1.0);
    pick = 0u;  // the cap is no element of the mesh
}
"""

EDGE_FRAGMENT = """
#version 330
uniform usampler2D edge_flags;
uniform int all_selected;
uniform int primitive_base;  // the first edge drawn (a frame may draw a range)
uniform vec3 edge_color;
uniform vec3 selected_color;
layout(location = 0) out vec4 color;
layout(location = 1) out uint pick;
""" + FETCH + """
void main() {
#ifdef PLAIN
    color = vec4(edge_color, 1.0);
    pick = 0u;
#else
    int primitive = primitive_base + gl_PrimitiveID;
    bool selected = all_selected != 0 || fetch(edge_flags, primitive) != 0u;
    color = vec4(selected ? selected_color : edge_color, 1.0);
    pick = (2u << 28) | uint(primitive + 1);
#endif
}
"""

POINT_FRAGMENT = """
#version 330
uniform usampler2D vertex_flags;
uniform vec3 point_color;
uniform vec3 selected_color;
uniform int use_flags;
flat in int v_vertex;
layout(location = 0) out vec4 color;
layout(location = 1) out uint pick;
""" + FETCH + """
void main() {
    bool selected = use_flags != 0 && fetch(vertex_flags, v_vertex) != 0u;
    color = vec4(selected ? selected_color : point_color, 1.0);
    pick = (3u << 28) | uint(v_vertex + 1);
}
"""

LINE_FRAGMENT = """
#version 330
uniform vec3 line_color;
layout(location = 0) out vec4 color;
layout(location = 1) out uint pick;
void main() {
    color = vec4(line_color, 1.0);
    pick = 0u;  // guides (grid, axes) are never picked
}
"""

TEXT_VERTEX = """
#version 330
uniform mat4 mvp;
uniform mat4 view;
uniform vec2 viewport;
uniform int screen_space;
uniform vec2 fade_range;
in vec2 in_corner;
in vec3 in_anchor;
in vec2 in_offset;
in vec2 in_size;
in vec4 in_uv;
in float in_kind;
in float in_selected;
out vec2 v_uv;
out float v_fade;
flat out int v_kind;
flat out int v_selected;
void main() {
    vec2 px = in_offset + in_corner * in_size;      // pixels, y down
    vec2 at = in_anchor.xy;
    v_fade = 1.0;
    if (screen_space == 0) {
        vec4 clip = mvp * vec4(in_anchor, 1.0);
        if (clip.w <= 0.0) { gl_Position = vec4(2.0, 2.0, 2.0, 1.0); return; }
        vec2 ndc = clip.xy / clip.w;
        // snap the anchor to a pixel so glyphs stay crisp and output is stable
        at = floor(vec2(ndc.x + 1.0, 1.0 - ndc.y) * 0.5 * viewport + 0.5);
        float depth = -(view * vec4(in_anchor, 1.0)).z;
        float t = clamp((depth - fade_range.x) / max(fade_range.y - fade_range.x, 1e-9),
                        0.0, 1.0);
        v_fade = 1.0 - 0.7 * t;
    }
    vec2 p = floor(at + px);
    gl_Position = vec4(p.x / viewport.x * 2.0 - 1.0, 1.0 - p.y / viewport.y * 2.0, 0.0, 1.0);
    v_uv = vec2(mix(in_uv.x, in_uv.z, in_corner.x), mix(in_uv.y, in_uv.w, in_corner.y));
    v_kind = int(in_kind + 0.5);
    v_selected = int(in_selected + 0.5);
}
"""

TEXT_FRAGMENT = """
#version 330
uniform sampler2D atlas;
uniform vec4 palette[16];
uniform vec4 highlight;
in vec2 v_uv;
in float v_fade;
flat in int v_kind;
flat in int v_selected;
out vec4 color;
void main() {
    vec4 tint = (v_selected != 0 && v_kind >= 8) ? highlight : palette[v_kind];
    float coverage = texture(atlas, v_uv).r;
    color = vec4(tint.rgb, tint.a * coverage * v_fade);
}
"""
