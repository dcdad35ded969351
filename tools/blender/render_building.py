"""Renders batches of labelled building meshes with Blender 3.4 (headless) for the lc2wf dataset.

Run:  blender -b --factory-startup --python-exit-code 1 --python render_building.py -- JOB.json

JOB.json (written by lc2wf-dataset --renderer blender; coordinates in metres, z up):
  {"engine": "BLENDER_WORKBENCH" | "BLENDER_EEVEE" | "CYCLES", "samples": 1, "shadows": true, "gt_views": true,
   "textures": "paper" (default: the paper-like look) | "sfm" (non-repeating noise for structure from motion)
               | "photo" (each building then has "photo": windows and doors per face, clutter objects,
               road and paths, sun, per-view exposure; written by tools/render/blender_renderer.cpp),
   "sun_azimuth_deg": 140, "sun_elevation_deg": 55,
   "buildings": [{"name": str, "out_dir": str, "seed": int, "vertices": [[x,y,z]...], "faces": [[i,...]...],
                  "labels": [1|2|3 ...], "edges": [[i,j]...] (into "gt_junctions": [[x,y,z]...], default the vertices),
                  "cameras": [{"K": [9 floats, row-major], "R": [9], "t": [3], "width": W, "height": H}...]}]}

Per building, in out_dir: view_000.png ..., cameras.json (K, R, t read back from Blender's cameras in the
OpenCV convention: x_cam = R X + t, pixel (0,0) at the centre of the top-left pixel), views.json (per view
the projected GT junctions and every GT edge as [i, j, visible, visible_fraction]; skipped with
"gt_views": false) and, last, done.json (with the seconds spent on scene set-up, renders and GT views).
A building that fails gets error.txt instead and the batch goes on; the exit code is non-zero only when
the job itself is unusable.
"""
import json
import math
import os
import sys
import time
import traceback

import bpy
import numpy as np
from mathutils import Matrix, Vector
from mathutils.bvhtree import BVHTree

ROOF, BASE, WALL = 1, 2, 3
R_BCAM2CV = Matrix(((1, 0, 0), (0, -1, 0), (0, 0, -1)))  # Blender camera looks down -Z with +Y up
TEX_PX_PER_M = 96


# ----------------------------------------------------------------------------- procedural textures
def _hash01(i, j, seed):
    h = (i.astype(np.uint64) * np.uint64(0x632BE59BD9B4E019) + j.astype(np.uint64) + np.uint64(seed)) & np.uint64(0xFFFFFFFFFFFFFFFF)
    h ^= h >> np.uint64(31)
    h *= np.uint64(0x94D049BB133111EB)
    h ^= h >> np.uint64(29)
    return (h >> np.uint64(40)).astype(np.float64) / float(1 << 24)


def _grid(width_m, height_m, px_per_m=TEX_PX_PER_M):
    w, h = int(round(width_m * px_per_m)), int(round(height_m * px_per_m))
    u, v = np.meshgrid((np.arange(w) + 0.5) / px_per_m, (np.arange(h) + 0.5) / px_per_m)
    return u, v


def roof_tiles(seed):
    """Terracotta tiles: grooves between tile columns run down the slope (v), weaker course lines across."""
    col, course_len = 0.32, 0.42
    u, v = _grid(col * 8, course_len * 8)
    course = np.floor(v / course_len)
    cu = (u + np.mod(course, 2) * 0.5 * col) / col
    across, down = cu - np.floor(cu), v / course_len - course
    shade = 0.88 + 0.12 * np.sin(across * math.pi)
    shade = np.where(across < 0.16, shade * 0.45, shade)
    shade = np.where(down > 0.9, shade * 0.7, shade)
    shade *= 0.9 + 0.2 * _hash01(np.floor(cu).astype(np.int64) % 8, course.astype(np.int64), seed)
    return np.stack([0.62 * shade, 0.22 * shade, 0.12 * shade], -1)


def siding(seed):
    board = 0.28
    u, z = _grid(3.0, board * 8)
    t = z / board - np.floor(z / board)
    shade = np.where(t < 0.12, 0.72, 1.0) * (0.9 + 0.1 * t)
    return np.stack([0.80 * shade, 0.79 * shade, 0.74 * shade], -1)


def brick(seed):
    row, length, mortar = 0.16, 0.42, 0.02
    u, z = _grid(length * 6, row * 12)
    r = np.floor(z / row)
    uu = u + np.mod(r, 2) * 0.5 * length
    is_mortar = (np.mod(z, row) < mortar) | (np.mod(uu, length) < mortar)
    j = 0.9 + 0.2 * _hash01(np.floor(uu / length).astype(np.int64), r.astype(np.int64), seed)
    rgb = np.stack([0.62 * j, 0.52 * j, 0.40 * j], -1)
    return np.where(is_mortar[..., None], np.array([0.82, 0.80, 0.76]), rgb)


def _value_noise(u, v, period, seed):
    """Smooth value noise on a _grid meshgrid (u, v); the lattice wraps with the tile so it repeats seamlessly."""
    n = int(round((u[0, 0] + u[0, -1]) / period))  # first + last texel centre = tile width in metres
    lattice = _hash01(np.arange(n)[None, :], np.arange(n)[:, None], seed)  # [row j, column i], hashed once
    x, y = u[0] / period, v[:, 0] / period  # separable grid: one coordinate per column / row
    ix, iy = np.floor(x).astype(np.int64), np.floor(y).astype(np.int64)
    tx, ty = x - ix, y - iy
    tx, ty = tx * tx * (3 - 2 * tx), ty * ty * (3 - 2 * ty)
    i0, i1, j0, j1 = ix % n, (ix + 1) % n, iy % n, (iy + 1) % n
    row0 = lattice[j0][:, i0] * (1 - tx) + lattice[j0][:, i1] * tx
    row1 = lattice[j1][:, i0] * (1 - tx) + lattice[j1][:, i1] * tx
    return row0 * (1 - ty)[:, None] + row1 * ty[:, None]


# Smooth surfaces need no fine texels: their noise varies over >= 0.4 m, and 3 cm is about a pixel on the
# building at our viewing distances (96 px/m grass alone took ~2.7 s per building).
SMOOTH_PX_PER_M = 32


def flat_roof(seed):
    u, v = _grid(8.0, 8.0, SMOOTH_PX_PER_M)
    n = 0.85 + 0.15 * _value_noise(u, v, 0.8, seed + 7)
    return np.stack([0.30 * n, 0.29 * n, 0.28 * n], -1)


def grass(seed):
    u, v = _grid(16.0, 16.0, SMOOTH_PX_PER_M)
    n = 0.6 * _value_noise(u, v, 1.6, seed + 11) + 0.4 * _value_noise(u, v, 0.4, seed + 13)
    s = 0.8 + 0.4 * n
    return np.stack([0.11 * s, 0.20 * s, 0.06 * s], -1)


def make_image(name, rgb):
    h, w, _ = rgb.shape
    img = bpy.data.images.new(name, width=w, height=h, alpha=False, float_buffer=True)
    img.colorspace_settings.name = "Linear"  # before the pixels: changing it afterwards clears them
    rgba = np.concatenate([rgb, np.ones((h, w, 1))], -1).astype(np.float32)
    img.pixels.foreach_set(rgba.ravel())  # rows bottom-up; the patterns do not care
    return img


def make_material(name, rgb, tile_m):
    """Image-textured material; tile_m = (width, height) in metres covered by one image tile."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes = m.node_tree.nodes
    img = make_image(name + "_img", rgb)
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = img
    tex.interpolation = "Closest"  # crisp tile and board edges, as in the rasteriser
    bsdf = nodes["Principled BSDF"]
    bsdf.inputs["Roughness"].default_value = 0.9
    bsdf.inputs["Specular"].default_value = 0.1
    m.node_tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    nodes.active = tex  # Workbench shows the active image texture node
    m.diffuse_color = tuple(float(c) for c in rgb.reshape(-1, 3).mean(0)) + (1.0,)
    return m, tile_m


# ----------------------------------------------------------------------------- SfM textures ("textures": "sfm")
# Photo-like surfaces for structure from motion: high-contrast multi-scale noise that never repeats
# across a face, a random UV offset per face so symmetric faces differ, and a non-repeating ground.
SFM_PX_PER_M = 32          # 3 cm texels: about one pixel at 20 m with a 35 mm lens at 640 px
SFM_TILE_M = 24.0          # 768 px = 3 * 2^8; wider than nearly every Roof-Image face, so a face rarely shows a patch twice
SFM_GROUND_TILE_M = 96.0   # 1152 px = 3 * 2^7 * 3; the ground around a building seen from the camera ring fits in one tile
SFM_GROUND_PX_PER_M = 12
SFM_TINTS = {"roof": (0.75, 0.35, 0.25), "flat": (0.55, 0.55, 0.58), "wall": (0.90, 0.85, 0.75),
             "base": (0.45, 0.45, 0.45), "ground": (0.40, 0.55, 0.30)}


def sfm_noise(size_px, rng, finest_px=3):
    """Sum of value-noise octaves (periods from finest_px doubling up to a quarter of the tile), equal
    weights, stretched to full contrast: blobs at every scale for SIFT. size_px should be finest_px
    times a power of two (times a small factor) so every period divides it and the tile is seamless."""
    out = np.zeros((size_px, size_px))
    period = finest_px
    while period <= size_px // 4:
        n = size_px // period
        lattice = rng.random((n, n))
        x = np.arange(size_px) / period
        i = np.floor(x).astype(np.int64)
        j = (i + 1) % n  # the lattice wraps, so the tile is seamless where UVs run past 1
        f = x - i
        f = f * f * (3 - 2 * f)
        rows = lattice[i] * (1 - f)[:, None] + lattice[j] * f[:, None]   # interpolate along y
        out += rows[:, i] * (1 - f)[None, :] + rows[:, j] * f[None, :]  # then along x
        period *= 2
    lo, hi = np.percentile(out[::4, ::4], [2, 98])  # a subsample is enough and 16x cheaper
    return np.clip((out - lo) / max(hi - lo, 1e-9), 0.0, 1.0)


def sfm_texture(kind, size_px, rng):
    lum = 0.08 + 0.92 * sfm_noise(size_px, rng)
    return np.asarray(SFM_TINTS[kind])[None, None, :] * lum[..., None]


def sfm_material(name, rgb):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    tex = m.node_tree.nodes.new("ShaderNodeTexImage")
    tex.image = make_image(name + "_img", rgb)
    tex.interpolation = "Linear"  # no texel aliasing: features must look alike from every view
    m.node_tree.links.new(tex.outputs["Color"], m.node_tree.nodes["Principled BSDF"].inputs["Base Color"])
    m.node_tree.nodes.active = tex
    m.diffuse_color = tuple(float(c) for c in rgb.reshape(-1, 3).mean(0)) + (1.0,)
    return m


def apply_sfm_textures(b, obj, ground, verts):
    """Replaces the building's and the ground's materials and UVs with SfM textures."""
    rng = np.random.default_rng(int(b.get("seed", 0)) + 1000003)
    me = obj.data
    me.materials.clear()
    slots = {}  # only the surfaces this building has: each texture costs seconds of numpy
    uv = me.uv_layers.active
    labels = b["labels"]
    for poly in me.polygons:
        pts = [verts[i] for i in poly.vertices]
        n, u, v = face_frame(pts)
        kind = surface_kind(labels[poly.index], n)
        if kind not in slots:
            slots[kind] = len(slots)
            me.materials.append(sfm_material("sfm_" + kind, sfm_texture(kind, int(SFM_TILE_M * SFM_PX_PER_M), rng)))
        poly.material_index = slots[kind]
        ou, ov = rng.random(2)
        for li in poly.loop_indices:
            d = verts[me.loops[li].vertex_index] - pts[0]
            uv.data[li].uv = (d.dot(u) / SFM_TILE_M + ou, d.dot(v) / SFM_TILE_M + ov)
    gme = ground.data
    gme.materials.clear()
    gme.materials.append(sfm_material("sfm_ground", sfm_texture("ground", int(SFM_GROUND_TILE_M * SFM_GROUND_PX_PER_M), rng)))
    guv = gme.uv_layers.active
    c = gme.vertices[0].co + (gme.vertices[2].co - gme.vertices[0].co) / 2  # the building's centre
    for li in gme.polygons[0].loop_indices:
        p = gme.vertices[gme.loops[li].vertex_index].co
        guv.data[li].uv = ((p.x - c.x) / SFM_GROUND_TILE_M + 0.5, (p.y - c.y) / SFM_GROUND_TILE_M + 0.5)


# ----------------------------------------------------------------------------- photo scene ("textures": "photo")
# The C++ side (tools/render/photo_scene.*) lays out the windows, doors and clutter; here they are painted
# into images: one per wall and per roof face, the ground and the road around the building, and a tile per
# kind of clutter object. Every surface carries the material detail of the rasteriser's photo textures
# (tools/render/photo_textures.cpp): octave value noise from a few centimetres up (plaster grain and
# stains, lichen on the tiles, grass tufts, asphalt grit, leaves), every tile, window and pane its own,
# so SIFT finds features on them and can tell them apart, as on real photos.
PHOTO_PX_PER_M = 32          # walls and clutter: 3 cm texels
PHOTO_ROOF_PX_PER_M = 48     # tile joints of 2-3 cm
PHOTO_GROUND_TILE_M = 96.0   # one tile centred on the building: nothing repeats near it
PHOTO_GRASS_PX_PER_M = 16
PHOTO_MARKS_PX_PER_M = 12    # asphalt, kerb and paving, in the same frame as the grass
PHOTO_CLUTTER_TILE_M = 12.0  # per kind of object; each face reads its own patch
PHOTO_PLASTERS = [(0.78, 0.74, 0.64), (0.82, 0.81, 0.78), (0.62, 0.62, 0.60), (0.75, 0.58, 0.36), (0.55, 0.30, 0.22)]
PHOTO_CARS = [(0.55, 0.05, 0.04), (0.06, 0.12, 0.40), (0.55, 0.56, 0.58), (0.03, 0.03, 0.03), (0.85, 0.85, 0.83)]
PHOTO_CURTAINS = [(0.85, 0.84, 0.80), (0.75, 0.68, 0.55), (0.55, 0.20, 0.15), (0.45, 0.50, 0.55), (0.90, 0.90, 0.88)]
PHOTO_GLASS = (0.07, 0.09, 0.12)
PHOTO_SKY_REFLECTION = (0.42, 0.47, 0.55)
# Per kind of clutter: its colour, and its detail's amount, finest period (m) and stretch along the face's v.
PHOTO_CLUTTER = {"chimney": ((0.45, 0.20, 0.13), 0.25, 0.03, 1.0), "balcony": ((0.72, 0.72, 0.70), 0.15, 0.03, 1.0),
                 "car_cabin": ((0.06, 0.07, 0.08), 0.5, 0.04, 1.0), "trunk": ((0.20, 0.13, 0.08), 0.35, 0.02, 4.0),
                 "neighbour_roof": ((0.30, 0.30, 0.31), 0.2, 0.04, 1.0)}
PHOTO_NEIGHBOUR_WALL = (0.70, 0.68, 0.62)  # plaster, as the building's walls


def octave_field(h, w, px_per_m, finest_m, octaves, rng, stretch=1.0):
    """Mean of `octaves` value-noise layers on an h x w texel grid, periods finest_m, 2 finest_m, ... metres
    (at least 2 texels; `stretch` times longer along the rows' axis), random lattices and phases, no wrap:
    nothing repeats inside the image. The numpy twin of value_noise.h's octave_noise."""
    out = np.zeros((h, w), dtype=np.float32)
    for k in range(octaves):
        px = max(2.0, finest_m * (2 ** k) * px_per_m)
        py = max(2.0, px * stretch)
        lattice = rng.random((int(math.ceil(h / py)) + 2, int(math.ceil(w / px)) + 2)).astype(np.float32)
        y, x = np.arange(h) / py + rng.random(), np.arange(w) / px + rng.random()
        iy, ix = np.floor(y).astype(np.int64), np.floor(x).astype(np.int64)
        fy, fx = (y - iy).astype(np.float32), (x - ix).astype(np.float32)
        fy, fx = fy * fy * (3 - 2 * fy), fx * fx * (3 - 2 * fx)
        rows = lattice[iy] * (1 - fy)[:, None] + lattice[iy + 1] * fy[:, None]
        out += rows[:, ix] * (1 - fx)[None, :] + rows[:, ix + 1] * fx[None, :]
    return out / octaves


def photo_detail(h, w, px_per_m, finest_m, octaves, rng, stretch=1.0):
    """Zero-mean detail in [-1, 1], stretched as photo_textures.cpp's detail() (standard deviation about 0.55)."""
    sd = 0.2 / math.sqrt(octaves)
    return np.clip(0.55 / sd * (octave_field(h, w, px_per_m, finest_m, octaves, rng, stretch) - 0.5), -1.0, 1.0)


def grained(rgb, amount, detail):
    """Colour(s) times (1 + amount x detail): an h x w x 3 image."""
    return np.asarray(rgb, dtype=np.float32) * np.maximum(0.0, 1.0 + amount * detail)[..., None]


def plaster_image(h, w, px, rgb, rng):
    """Plaster: stains over metres, grain from 4 cm up and damp patches of 10-50 cm with soft edges."""
    stains = 0.88 + 0.12 * octave_field(h, w, px, 1.6, 1, rng)
    patches = np.clip((octave_field(h, w, px, 0.12, 3, rng) - 0.56) * 12, 0, 1)
    return grained(rgb, 0.3, photo_detail(h, w, px, 0.04, 6, rng)) * (stains * (1 - 0.22 * patches))[..., None]


def facade_image(f, umin, zmin, w, h, plaster, frame_rgb, gutters, rng):
    """Wall image of w x h texels from (umin, zmin): grained plaster with stains and damp patches, sills,
    framed windows each with its own glass, patches of mirrored sky and curtain, wooden doors, the gutter."""
    px = PHOTO_PX_PER_M
    u = umin + (np.arange(w) + 0.5) / px
    z = zmin + (np.arange(h) + 0.5) / px
    hs = f["storey_height"]
    img = plaster_image(h, w, px, plaster, rng)
    img[z < f["ground_z"] + 0.15 * hs] *= 0.7
    glass = photo_detail(h, w, px, 0.04, 4, rng)  # every window shows its own part of it
    reflections = octave_field(h, w, px, 0.08, 3, rng)  # bright patches of mirrored sky and clouds

    def box(u0, u1, z0, z1):
        cols, rows = np.nonzero((u >= u0) & (u <= u1))[0], np.nonzero((z >= z0) & (z <= z1))[0]
        return (slice(rows[0], rows[-1] + 1), slice(cols[0], cols[-1] + 1)) if len(cols) and len(rows) else None

    def paint(u0, u1, z0, z1, rgb):
        b = box(u0, u1, z0, z1)
        if b is not None:
            img[b] = rgb

    sill = grained((0.70, 0.70, 0.68), 0.1, photo_detail(h, w, px, 0.03, 3, rng))
    for u0, u1, z0, z1 in f["windows"]:
        b = box(u0 - 0.06 * hs, u1 + 0.06 * hs, z0 - 0.06 * hs, z0)
        if b is not None:
            img[b] = sill[b]
        paint(u0, u1, z0, z1, frame_rgb)
        b = box(u0 + 0.04 * hs, u1 - 0.04 * hs, z0 + 0.04 * hs, z1 - 0.04 * hs)
        if b is not None:
            s = ((u[b[1]] - u0) / (u1 - u0))[None, :]
            t = ((z[b[0]] - z0) / (z1 - z0))[:, None]
            sky = (0.8 + 0.6 * t) * (0.7 + 0.6 * rng.random()) * np.ones_like(s)
            share = 0.5 * (rng.random() - 0.3)  # how much of this window mirrors the sky
            mirror = 0.85 * np.clip((reflections[b] - 0.5) * 6 + share, 0, 1)[..., None]
            img[b] = grained(PHOTO_GLASS, 0.45, glass[b]) * sky[..., None] * (1 - mirror) + np.asarray(PHOTO_SKY_REFLECTION, dtype=np.float32) * mirror
            kind, cover = rng.random(), 0.15 + 0.3 * rng.random()
            drawn = ((s < cover) | (s > 1 - cover)) if kind < 0.3 else (t < 0.25 + cover) if kind < 0.45 else (t > 1 - cover) if kind < 0.6 else None
            if drawn is not None:
                drawn = np.broadcast_to(drawn, sky.shape)
                cloth = np.asarray(PHOTO_CURTAINS[int(rng.integers(len(PHOTO_CURTAINS)))], dtype=np.float32)
                img[b] = np.where(drawn[..., None], cloth * (1 + 0.15 * glass[b])[..., None], img[b])
        mid, transom = 0.5 * (u0 + u1), z0 + 0.7 * (z1 - z0)
        paint(mid - 0.012 * hs, mid + 0.012 * hs, z0, z1, frame_rgb)
        paint(u0, u1, transom - 0.012 * hs, transom + 0.012 * hs, frame_rgb)
    for u0, u1, z0, z1 in f["doors"]:
        paint(u0 - 0.04 * hs, u1 + 0.04 * hs, z0, z1 + 0.04 * hs, frame_rgb)
        b = box(u0, u1, z0, z1)
        if b is not None:  # wood, its grain along the height
            img[b] = grained((0.22, 0.12, 0.06), 0.3, photo_detail(b[0].stop - b[0].start, b[1].stop - b[1].start, px, 0.01, 4, rng, 8.0))
        mid = z0 + 0.5 * (z1 - z0)
        paint(u0, u1, mid - 0.01 * hs, mid + 0.01 * hs, (0.05, 0.03, 0.02))
    if gutters and f["peak_z"] - f["top_z"] < 0.05 * hs:
        top = z > f["top_z"] - 0.07 * hs
        img[top] = grained((0.10, 0.10, 0.10), 0.2, photo_detail(int(top.sum()), w, px, 0.03, 4, rng))
    return img


def roof_image(umin, vmin, w, h, rgb, tiles, rng):
    """Roof face image of w x h texels from (umin, vmin) (u along the eave, v down the slope): the paper
    look's tiles (grooves down the slope, weaker course lines), every tile its own shade, under weathering,
    lichen and grit; without `tiles` a plain weathered roof."""
    px = PHOTO_ROOF_PX_PER_M
    u = umin + (np.arange(w) + 0.5) / px
    v = vmin + (np.arange(h) + 0.5) / px
    weather = (0.85 + 0.2 * octave_field(h, w, px, 2.5, 1, rng)) * (1 + 0.22 * photo_detail(h, w, px, 0.04, 6, rng))
    if not tiles:
        return np.asarray(rgb, dtype=np.float32) * (weather * (0.9 + 0.15 * octave_field(h, w, px, 0.11, 1, rng)))[..., None]
    col, course_len = 0.32, 0.42  # as roof_tiles()
    course = np.floor(v / course_len)[:, None]
    cu = (u[None, :] + np.mod(course, 2) * 0.5 * col) / col
    across, down = cu - np.floor(cu), v[:, None] / course_len - course
    shade = 0.88 + 0.12 * np.sin(across * math.pi)
    shade = np.where(across < 0.16, shade * 0.45, shade)
    shade = np.where(down > 0.9, shade * 0.7, shade)
    off = rng.integers(1 << 20, size=2)
    shade *= 0.85 + 0.3 * _hash01(np.floor(cu).astype(np.int64) + off[0], course.astype(np.int64) + off[1], int(rng.integers(1 << 30)))
    return np.asarray(rgb, dtype=np.float32) * (shade * weather)[..., None]


def clutter_tile(kind, rng, car=None):
    """One tile of a kind of clutter object (`car`: a car body's colour): its colour with detail; foliage
    has leaf clumps and single leaves, neighbouring walls are plaster."""
    px, n = PHOTO_PX_PER_M, int(PHOTO_CLUTTER_TILE_M * PHOTO_PX_PER_M)
    if kind == "foliage":
        clumps = 0.6 * octave_field(n, n, px, 0.4, 1, rng) + 0.4 * octave_field(n, n, px, 0.11, 1, rng)
        return grained((0.10, 0.22, 0.06), 0.45, photo_detail(n, n, px, 0.03, 4, rng)) * (0.45 + 0.9 * clumps)[..., None]
    if kind == "car_body":
        return grained(car, 0.08, photo_detail(n, n, px, 0.05, 4, rng))
    if kind == "neighbour_wall":
        return plaster_image(n, n, px, PHOTO_NEIGHBOUR_WALL, rng)
    rgb, amount, finest, stretch = PHOTO_CLUTTER[kind]
    return grained(rgb, amount, photo_detail(n, n, px, finest, 5, rng, stretch)) * (0.9 + 0.1 * octave_field(n, n, px, 0.3, 1, rng))[..., None]


def add_flat_object(scene, name, verts, faces, materials, indices, z_lift=0.0):
    me = bpy.data.meshes.new(name)
    me.from_pydata([(x, y, zz + z_lift) for x, y, zz in verts], [], [list(f) for f in faces])
    me.validate(clean_customdata=False)
    for m in materials:
        me.materials.append(m)
    for poly, k in zip(me.polygons, indices):
        poly.material_index = k
    obj = bpy.data.objects.new(name, me)
    scene.collection.objects.link(obj)
    return obj


def face_extent(pts, uax, vax):
    """Face coordinates of the points (along uax, and along vax or world z when vax is None) and their minima."""
    us = [(q - pts[0]).dot(uax) for q in pts]
    vs = [q.z for q in pts] if vax is None else [(q - pts[0]).dot(vax) for q in pts]
    return us, vs, min(us), min(vs), max(us) - min(us), max(vs) - min(vs)


def texel_size(metres, px):
    return max(2, min(4096, int(math.ceil(metres * px))))


def apply_photo_scene(b, scene, obj, verts):
    """Walls with windows and doors, roofs, the ground with the road and paths, the clutter objects."""
    p = b["photo"]
    seed = int(b.get("seed", 0))
    rng = np.random.default_rng(seed + 7000003)
    plaster = PHOTO_PLASTERS[int(rng.integers(len(PHOTO_PLASTERS)))]
    frame_rgb = (0.12, 0.12, 0.12) if rng.random() < 1 / 3 else (0.86, 0.86, 0.84)
    me = obj.data
    uv = me.uv_layers.active

    def own_material(poly, name, img, px, us, vs, umin, vmin, w, h):
        me.materials.append(sfm_material(name, img))  # image texture, linear filtering
        poly.material_index = len(me.materials) - 1
        for li, uu, vv in zip(poly.loop_indices, us, vs):
            uv.data[li].uv = ((uu - umin) * px / w, (vv - vmin) * px / h)

    for poly in me.polygons:
        f = p["facades"][poly.index]
        pts = [verts[i] for i in poly.vertices]
        n, uax, vax = face_frame(pts)
        kind = surface_kind(b["labels"][poly.index], n)
        if kind in ("roof", "flat"):
            us, vs, umin, vmin, wm, hm = face_extent(pts, uax, vax)
            w, h = texel_size(wm, PHOTO_ROOF_PX_PER_M), texel_size(hm, PHOTO_ROOF_PX_PER_M)
            img = roof_image(umin, vmin, w, h, (0.30, 0.29, 0.28) if kind == "flat" else (0.62, 0.22, 0.12),
                             kind == "roof" and p.get("roof_tiles", True), rng)
            own_material(poly, f"roof_{poly.index}", img, PHOTO_ROOF_PX_PER_M, us, vs, umin, vmin, w, h)
            continue
        if kind != "wall":
            continue
        us, zs, umin, zmin, wm, hm = face_extent(pts, uax, None)
        w, h = texel_size(wm, PHOTO_PX_PER_M), texel_size(hm, PHOTO_PX_PER_M)
        if f["wall"]:
            img = facade_image(f, umin, zmin, w, h, plaster, frame_rgb, p.get("gutters", True), rng)
        else:  # gable triangles and other walls without storeys: grained plaster, as in the rasteriser
            img = plaster_image(h, w, PHOTO_PX_PER_M, tuple(0.9 * c for c in plaster), rng)
        own_material(poly, f"facade_{poly.index}", img, PHOTO_PX_PER_M, us, zs, umin, zmin, w, h)

    # The ground: one grass image centred on the building, and the road, kerbs and paving in the same frame.
    zground = min(v.z for v in verts)
    ground = bpy.data.objects["ground"].data
    centre = ground.vertices[0].co + (ground.vertices[2].co - ground.vertices[0].co) / 2

    def ground_uv(x, y):
        return ((x - centre.x) / PHOTO_GROUND_TILE_M + 0.5, (y - centre.y) / PHOTO_GROUND_TILE_M + 0.5)

    n = int(PHOTO_GROUND_TILE_M * PHOTO_GRASS_PX_PER_M)
    patches = (0.5 * octave_field(n, n, PHOTO_GRASS_PX_PER_M, 2.0, 1, rng) + 0.3 * octave_field(n, n, PHOTO_GRASS_PX_PER_M, 0.45, 1, rng) +
               0.2 * octave_field(n, n, PHOTO_GRASS_PX_PER_M, 0.125, 1, rng))
    dry = np.clip((octave_field(n, n, PHOTO_GRASS_PX_PER_M, 0.25, 3, rng) - 0.56) * 12, 0, 1)[..., None]  # dry spots of 0.2-1 m
    grass_img = (np.asarray((0.11, 0.20, 0.06), dtype=np.float32) + dry * np.asarray((0.12, 0.02, 0.03), dtype=np.float32)) * \
        (np.maximum(0.0, 1.0 + 0.35 * photo_detail(n, n, PHOTO_GRASS_PX_PER_M, 0.03, 6, rng)) * (0.6 + 0.8 * patches))[..., None]
    ground.materials.clear()
    ground.materials.append(sfm_material("photo_grass", grass_img))
    guv = ground.uv_layers.active
    for li in ground.polygons[0].loop_indices:
        co = ground.vertices[ground.loops[li].vertex_index].co
        guv.data[li].uv = ground_uv(co.x, co.y)

    quads, idx = [], []

    def strip(a, d, half, length, k):
        d = Vector((d[0], d[1], 0)).normalized()
        s = Vector((-d.y, d.x, 0)) * half
        a = Vector((a[0], a[1], 0))
        pieces = max(1, int(math.ceil(length / 4.0)))  # short pieces: Workbench streaks long thin polygons
        for i in range(pieces):
            p0, p1 = a + d * (length * i / pieces), a + d * (length * (i + 1) / pieces)
            quads.append([tuple(p0 - s), tuple(p0 + s), tuple(p1 + s), tuple(p1 - s)])
            idx.append(k)

    road = p.get("road")
    m = int(PHOTO_GROUND_TILE_M * PHOTO_MARKS_PX_PER_M)
    asphalt = grained((0.10, 0.10, 0.11), 0.3, photo_detail(m, m, PHOTO_MARKS_PX_PER_M, 0.03, 7, rng)) * \
        (0.9 + 0.2 * octave_field(m, m, PHOTO_MARKS_PX_PER_M, 0.33, 1, rng))[..., None]
    kerb = grained((0.60, 0.60, 0.58), 0.15, photo_detail(m, m, PHOTO_MARKS_PX_PER_M, 0.03, 5, rng))
    paving = grained((0.50, 0.49, 0.46), 0.15, photo_detail(m, m, PHOTO_MARKS_PX_PER_M, 0.03, 5, rng))
    mats = [sfm_material("asphalt", asphalt), sfm_material("kerb", kerb), sfm_material("paving", paving)]
    if road:
        d, c, hw = Vector((road["dir"][0], road["dir"][1], 0)), road["point"], road["half_width"]
        side = Vector((-d.y, d.x, 0))
        start = Vector((c[0], c[1], 0)) - d * 150.0
        hs = p["storey_height"]
        strip((start + side * (hw + 0.33 * hs)), d, 0.27 * hs, 300.0, 2)
        strip((start - side * (hw + 0.33 * hs)), d, 0.27 * hs, 300.0, 2)
        strip((start + side * (hw + 0.03 * hs)), d, 0.03 * hs, 300.0, 1)
        strip((start - side * (hw + 0.03 * hs)), d, 0.03 * hs, 300.0, 1)
        strip(start, d, hw, 300.0, 0)
    for x0, y0, x1, y1 in p.get("paths", []):
        strip((x0, y0), (x1 - x0, y1 - y0), p["path_half_width"], math.hypot(x1 - x0, y1 - y0), 2)
    if quads:
        qv = [q for quad in quads for q in quad]
        marks = add_flat_object(scene, "ground_marks", qv, [[4 * i, 4 * i + 1, 4 * i + 2, 4 * i + 3] for i in range(len(quads))], mats, idx,
                                zground + 0.03)
        muv = marks.data.uv_layers.new(name="uv")
        for poly in marks.data.polygons:
            for li in poly.loop_indices:
                co = marks.data.vertices[marks.data.loops[li].vertex_index].co
                muv.data[li].uv = ground_uv(co.x, co.y)

    kinds, objects = p["clutter_kinds"], p["clutter_objects"]
    if kinds:
        cverts = [Vector(v) for v in p["clutter_vertices"]]
        names = sorted(set(kinds) - {"car_body"})
        cmats = [sfm_material("clutter_" + k, clutter_tile(k, rng)) for k in names]
        cmats += [sfm_material(f"car_{i}", clutter_tile("car_body", rng, c)) for i, c in enumerate(PHOTO_CARS)]
        index, face_uvs = [], []
        for face, k, o in zip(p["clutter_faces"], kinds, objects):
            pts = [cverts[i] for i in face]
            _, uax, vax = face_frame(pts)
            index.append(names.index(k) if k != "car_body" else len(names) + int(o) % len(PHOTO_CARS))
            ou, ov = rng.random(2)  # each face its own patch of its kind's tile
            face_uvs.append([((q - pts[0]).dot(uax) / PHOTO_CLUTTER_TILE_M + ou, (q - pts[0]).dot(vax) / PHOTO_CLUTTER_TILE_M + ov)
                             for q in pts])
        cobj = add_flat_object(scene, "clutter", p["clutter_vertices"], p["clutter_faces"], cmats, index)
        cuv = cobj.data.uv_layers.new(name="uv")
        for poly, uvs in zip(cobj.data.polygons, face_uvs):
            for li, t in zip(poly.loop_indices, uvs):
                cuv.data[li].uv = t


# ----------------------------------------------------------------------------- scene
def face_frame(pts):
    """Unit normal (Newell), horizontal in-plane axis u and down-slope axis v (as in the C++ rasteriser)."""
    n = Vector((0.0, 0.0, 0.0))
    for a, b in zip(pts, pts[1:] + pts[:1]):
        n.x += (a.y - b.y) * (a.z + b.z)
        n.y += (a.z - b.z) * (a.x + b.x)
        n.z += (a.x - b.x) * (a.y + b.y)
    n = n.normalized() if n.length > 0 else Vector((0, 0, 1))
    if abs(n.z) > 0.985:
        return n, Vector((1, 0, 0)), Vector((0, 1, 0))
    u = n.cross(Vector((0, 0, 1))).normalized()
    v = n.cross(u).normalized()
    if v.z > 0:
        v = -v
    return n, u, v


def surface_kind(label, n):
    if label == BASE:
        return "base"
    if abs(n.z) > 0.985:
        return "flat" if label == ROOF else "base"
    if label == ROOF and abs(n.z) > 0.1:
        return "roof"
    return "wall"


def build_scene(b, job):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    seed = int(b.get("seed", 0))
    wall_style = brick if (seed >> 3) % 3 == 0 else siding
    mats = {
        "roof": make_material("roof", roof_tiles(seed), (0.32 * 8, 0.42 * 8)),
        "flat": make_material("flat", flat_roof(seed), (8.0, 8.0)),
        "wall": make_material("wall", wall_style(seed), (0.42 * 6, 0.16 * 12) if wall_style is brick else (3.0, 0.28 * 8)),
        "base": make_material("base", np.full((4, 4, 3), 0.25), (1.0, 1.0)),
        "grass": make_material("grass", grass(seed), (16.0, 16.0)),
    }
    order = ["roof", "flat", "wall", "base"]
    verts = [Vector(v) for v in b["vertices"]]
    faces, labels = b["faces"], b["labels"]
    if len(faces) != len(labels):
        raise ValueError(f"{len(faces)} faces but {len(labels)} labels")
    me = bpy.data.meshes.new(b["name"])
    me.from_pydata([tuple(v) for v in verts], [], [list(f) for f in faces])  # n-gons: no diagonal edges
    me.validate(clean_customdata=False)
    obj = bpy.data.objects.new(b["name"], me)
    scene.collection.objects.link(obj)
    for k in order:
        me.materials.append(mats[k][0])
    uv = me.uv_layers.new(name="uv")
    for poly in me.polygons:
        pts = [verts[i] for i in poly.vertices]
        n, u, v = face_frame(pts)
        kind = surface_kind(labels[poly.index], n)
        poly.material_index = order.index(kind)
        tw, th = mats[kind][1]
        # Same per-face pattern shift as the rasteriser (golden-ratio sequence, metres).
        ou = math.fmod(poly.index * 0.6180339887, 1.0) * 7.3
        ov = math.fmod(poly.index * 0.7548776662, 1.0) * 5.9
        for li in poly.loop_indices:
            p = verts[me.loops[li].vertex_index]
            d = p - pts[0]
            if kind == "wall":  # boards and bricks follow world height, like the rasteriser
                uv.data[li].uv = ((d.dot(u) + ou) / tw, p.z / th)
            elif kind == "flat":
                uv.data[li].uv = (p.x / tw, p.y / th)
            else:
                uv.data[li].uv = ((d.dot(u) + ou) / tw, (d.dot(v) + ov) / th)
    # Ground: a large grass square at the lowest vertex, UVs in metres / tile size.
    zmin = min(v.z for v in verts)
    cx = sum(v.x for v in verts) / len(verts)
    cy = sum(v.y for v in verts) / len(verts)
    half = 400.0
    gme = bpy.data.meshes.new("ground")
    gv = [(cx - half, cy - half, zmin), (cx + half, cy - half, zmin), (cx + half, cy + half, zmin), (cx - half, cy + half, zmin)]
    gme.from_pydata(gv, [], [[0, 1, 2, 3]])
    gme.materials.append(mats["grass"][0])
    guv = gme.uv_layers.new(name="uv")
    for li, (x, y, _) in zip(gme.polygons[0].loop_indices, gv):
        guv.data[li].uv = (x / 16.0, y / 16.0)
    ground = bpy.data.objects.new("ground", gme)
    scene.collection.objects.link(ground)
    # Lower the ground a hair so it never z-fights with the base polygon.
    ground.location.z = -1e-3
    return scene, obj, verts


def sun_direction(job):
    """Unit vector towards the sun (world frame)."""
    az, el = math.radians(job.get("sun_azimuth_deg", 140.0)), math.radians(job.get("sun_elevation_deg", 55.0))
    return Vector((math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)))


def setup_render(scene, job, width, height):
    engine = job.get("engine", "BLENDER_WORKBENCH")
    samples = int(job.get("samples", 1))
    shadows = bool(job.get("shadows", True))
    sun_dir = sun_direction(job)
    r = scene.render
    r.engine = engine
    r.resolution_x, r.resolution_y, r.resolution_percentage = width, height, 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.image_settings.file_format = "PNG"
    r.image_settings.color_mode = "RGB"
    r.dither_intensity = 1.0
    scene.view_settings.view_transform = "Standard"
    world = bpy.data.worlds.new("world")
    world.color = (0.55, 0.65, 0.80)
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.55, 0.65, 0.80, 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.6
    scene.world = world
    if engine == "BLENDER_WORKBENCH":
        sh = scene.display.shading
        sh.light = "STUDIO"
        sh.color_type = "TEXTURE"
        sh.show_shadows = shadows
        sh.shadow_intensity = 0.6
        # Workbench maps light_direction (a, b, c) to the light's travel direction (-a, c, -b) in world
        # space (matches the shadows seen in renders), so this casts them away from the sun.
        scene.display.light_direction = (sun_dir.x, sun_dir.z, -sun_dir.y)
        # Each anti-aliasing sample is a full llvmpipe pass (~0.07 s at 640x480); 1 = "OFF".
        scene.display.render_aa = "OFF" if samples == 1 else str(samples) if str(samples) in ("5", "8", "11", "16", "32") else "8"
    else:
        sun = bpy.data.lights.new("sun", type="SUN")
        sun.energy = 4.0
        sun.angle = 0.01 if shadows else 0.0
        sun_obj = bpy.data.objects.new("sun", sun)
        sun_obj.rotation_euler = (-sun_dir).to_track_quat("-Z", "Y").to_euler()
        scene.collection.objects.link(sun_obj)
        if engine == "CYCLES":
            scene.cycles.samples = samples
            scene.cycles.device = "CPU"
            scene.cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise
            sun.cycles.cast_shadow = shadows
        else:
            scene.eevee.taa_render_samples = samples
            scene.eevee.use_soft_shadows = False
            sun.use_shadow = shadows


def place_camera(scene, cam_obj, K, R, t, width, height):
    """Blender camera from OpenCV K, R, t (square pixels, horizontal sensor fit)."""
    fx, fy, cx, cy = K[0][0], K[1][1], K[0][2], K[1][2]
    if abs(fx - fy) > 1e-6 * fx or abs(K[0][1]) > 1e-9:
        raise ValueError("cameras must have square pixels and no skew")
    cd = cam_obj.data
    cd.sensor_fit = "HORIZONTAL"
    cd.sensor_width = 36.0
    cd.lens = fx * cd.sensor_width / width
    cd.shift_x = (width / 2.0 - 0.5 - cx) / width
    cd.shift_y = (cy - height / 2.0 + 0.5) / width
    cd.clip_start, cd.clip_end = 0.05, 1000.0
    R = Matrix(R)
    R_w2b = R_BCAM2CV @ R
    C = -(R.transposed() @ Vector(t))
    cam_obj.matrix_world = Matrix.Translation(C) @ R_w2b.transposed().to_4x4()
    bpy.context.view_layer.update()  # matrix_world is stale otherwise


def camera_to_opencv(scene, cam_obj):
    """K, R, t of a Blender camera; -0.5 because Blender's pixel centres sit at +0.5."""
    r = scene.render
    s = r.resolution_percentage / 100.0
    w, h = r.resolution_x * s, r.resolution_y * s
    par = r.pixel_aspect_y / r.pixel_aspect_x
    cd = cam_obj.data
    fit = cd.sensor_fit
    if fit == "AUTO":
        fit = "HORIZONTAL" if r.pixel_aspect_x * w >= r.pixel_aspect_y * h else "VERTICAL"
    sensor = cd.sensor_height if fit == "VERTICAL" else cd.sensor_width
    view = w if fit == "HORIZONTAL" else par * h
    fx = cd.lens / sensor * view
    fy = fx / par
    cx = w / 2.0 - cd.shift_x * view - 0.5
    cy = h / 2.0 + cd.shift_y * view / par - 0.5
    loc, rot = cam_obj.matrix_world.decompose()[0:2]
    R_w2b = rot.to_matrix().transposed()
    t_w2b = -1.0 * (R_w2b @ loc)
    R = R_BCAM2CV @ R_w2b
    t = R_BCAM2CV @ t_w2b
    return [[fx, 0.0, cx], [0.0, fy, cy], [0.0, 0.0, 1.0]], [list(row) for row in R], list(t)


def project(K, R, t, X):
    xc = Matrix(R) @ X + Vector(t)
    return [K[0][0] * xc.x / xc.z + K[0][2], K[1][1] * xc.y / xc.z + K[1][2]], xc.z


def edge_visibility(bvh, K, R, t, w, h, a, b, samples=16, tol=0.02):
    """Fraction of samples on edge (a, b) in front of the camera, inside the image and not hidden."""
    R = np.asarray(R, dtype=np.float64)
    t = np.asarray(t, dtype=np.float64)
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    # Projection of all samples at once; only the in-frame ones need a (Python-level) ray cast.
    X = a + np.outer((np.arange(samples) + 0.5) / samples, b - a)
    xc = X @ R.T + t
    z = xc[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        u = K[0][0] * xc[:, 0] / z + K[0][2]
        v = K[1][1] * xc[:, 1] / z + K[1][2]
    inside = (z > 0) & (u >= -0.5) & (u <= w - 0.5) & (v >= -0.5) & (v <= h - 0.5)
    C = -(R.T @ t)
    Cv = Vector(C)
    seen = 0
    for X_k in X[inside]:
        d = X_k - C
        dist = float(np.linalg.norm(d))
        if bvh.ray_cast(Cv, Vector(d / dist), dist - tol)[0] is None:
            seen += 1
    return seen / samples


def render_building(b, job):
    t0 = time.time()
    out = b["out_dir"]
    os.makedirs(out, exist_ok=True)
    cams = b["cameras"]
    if not cams:
        raise ValueError("no cameras")
    width, height = int(cams[0]["width"]), int(cams[0]["height"])
    scene, obj, verts = build_scene(b, job)
    photo = b.get("photo") if job.get("textures", "paper") == "photo" else None
    if photo and photo.get("vary_sun", False):
        job = dict(job, sun_azimuth_deg=photo["sun_azimuth_deg"], sun_elevation_deg=photo["sun_elevation_deg"])
    setup_render(scene, job, width, height)
    if job.get("textures", "paper") == "sfm":
        apply_sfm_textures(b, obj, bpy.data.objects["ground"], verts)
    if photo:
        apply_photo_scene(b, scene, obj, verts)
    cam_obj = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(cam_obj)
    scene.camera = cam_obj
    with_gt = bool(job.get("gt_views", True))  # views.json is only wanted when the renders are kept
    # GT edges index these, not the repaired mesh's vertices
    gt_junctions = [Vector(v) for v in b["gt_junctions"]] if "gt_junctions" in b else verts
    bvh = BVHTree.FromPolygons([tuple(v) for v in verts], [list(f) for f in b["faces"]]) if with_gt else None
    t_scene = time.time()
    t_render = t_gt = 0.0
    exported, views = [], []
    for i, c in enumerate(cams):
        if int(c["width"]) != width or int(c["height"]) != height:
            raise ValueError(f"camera {i} has a different image size")
        K = [c["K"][0:3], c["K"][3:6], c["K"][6:9]]
        R = [c["R"][0:3], c["R"][3:6], c["R"][6:9]]
        place_camera(scene, cam_obj, K, R, c["t"], width, height)
        scene.render.filepath = os.path.join(out, f"view_{i:03d}.png")
        if photo:
            scene.view_settings.exposure = math.log2(photo["exposure"][i])  # per-view exposure change
        t1 = time.time()
        bpy.ops.render.render(write_still=True)
        t_render += time.time() - t1
        K2, R2, t2 = camera_to_opencv(scene, cam_obj)
        exported.append({"K": [x for row in K2 for x in row], "R": [x for row in R2 for x in row], "t": t2,
                         "width": width, "height": height})
        if not with_gt:
            continue
        t1 = time.time()
        junc2d = [project(K2, R2, t2, v)[0] for v in gt_junctions]
        edges = []
        for a, bb in b.get("edges", []):
            frac = edge_visibility(bvh, K2, R2, t2, width, height, gt_junctions[a], gt_junctions[bb])
            edges.append([a, bb, 1 if frac >= 0.5 else 0, round(frac, 4)])
        views.append({"junc2D": junc2d, "edges": edges})
        t_gt += time.time() - t1
    with open(os.path.join(out, "cameras.json"), "w") as f:
        json.dump(exported, f)
    if with_gt:
        with open(os.path.join(out, "views.json"), "w") as f:
            json.dump(views, f)
    with open(os.path.join(out, "done.json"), "w") as f:
        json.dump({"views": len(cams), "seconds": time.time() - t0, "seconds_scene": t_scene - t0,
                   "seconds_render": t_render, "seconds_gt_views": t_gt}, f)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 1:
        raise SystemExit("usage: blender -b --factory-startup --python-exit-code 1 --python render_building.py -- JOB.json")
    with open(argv[0]) as f:
        job = json.load(f)
    failed = 0
    for b in job["buildings"]:
        try:
            render_building(b, job)
        except Exception:  # one bad building must not stop the batch
            failed += 1
            os.makedirs(b["out_dir"], exist_ok=True)
            with open(os.path.join(b["out_dir"], "error.txt"), "w") as f:
                f.write(traceback.format_exc())
    print(f"render_building: {len(job['buildings']) - failed} rendered, {failed} failed", flush=True)


main()
