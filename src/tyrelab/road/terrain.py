"""The terrain interface: everything a compiled contact model may ask of the ground.

The contact models (``tyre/contact``, ``tyre/ring``) never read a road's data:
they call the functions below with the *terrain record* a wheel carries
(``Wheel.road``), and numba picks, at compile time, the functions registered
for that record's type (:func:`register_terrain`), as it picks a contact model
by its parameter record (ARCHITECTURE.md, "The registry and compiled
dispatch"). A rig loop compiles once per combination of tyre model and kind of
ground and is cached as such; no terrain id or flag exists at run time. The
rigid bilinear grid (:class:`~tyrelab.road.grid.RoadSurface`, registered as
``"rigid"`` in :mod:`tyrelab.road.grid`) is the first kind. The soil bed of
:mod:`tyrelab.road.soil` (the rigid wheel's ground, which that model queries
through its own step) is not registered yet: registered with these functions
and a ``contact``, it would take every tyre model without one being edited.

Why these functions and not just ``height``: the models are exact on a
piecewise-linear ground and fast because they skip ground no tyre part can
reach. Both rest on structure the ground must describe, so the interface
names that structure in terms any terrain can provide:

Queries at a point
    :func:`terrain_height`, :func:`terrain_height_gradient`,
    :func:`terrain_penetration` (height and gradient only below a query
    point: the ring's tread strips), :func:`terrain_friction` (a scale on
    the tyre's friction, 1 on the rigid road).
Bounds (what lets a search skip ground)
    :func:`terrain_zmax` (over all y, for x in a range),
    :func:`terrain_range` (everywhere; equal bounds mean one level plane),
    :func:`terrain_blocks` / :func:`terrain_block_max` (the bounds per block
    of x that :func:`terrain_zmax` is made of, for searches that walk
    block by block).
The lattice (what makes the models exact)
    :func:`terrain_lines`: break lines ``x_k = x_first + k spacing``, ``k =
    0 .. count-1``: along any line of constant y the height is linear in x
    between consecutive break lines and constant beyond the first and the
    last. :func:`terrain_row` names such a line by a handle ``(row,
    weight)`` (an int and a float whose meaning only the terrain knows; the
    grid: between node rows ``row`` and ``row + 1`` at ``weight``);
    :func:`terrain_line_height` is the height at break line k on it,
    :func:`terrain_row_height` at any x on it. A smooth terrain gives a
    fine lattice and is then treated as piecewise linear at that resolution;
    a lattice finer than the true breaks is always exact.
Deformation
    :func:`terrain_is_rigid` (a compile-time constant) and
    :func:`terrain_contact`: the ground's answer to a tyre element pressing
    on it, which a deformable ground uses to sink (keeping its state) and to
    carry no more than it bears. For a rigid kind it is the identity, and the
    models call it only behind ``if not terrain_is_rigid(road)``, so on the
    rigid road the branch is not even in the machine code: rigid runs compile
    to the code they compiled to before the interface existed.

Every interface function is an ``@overload(..., inline="always")`` whose body
calls the registered function: the caller's code is the registered function's
code (a call where that function is a plain ``njit``, its body where it is
``inline="always"``), so the interface adds no run time and a query inlined
into a kernel keeps that kernel's compile flags.
:func:`terrain_row_height` is derived from the lattice (a plain inline
function), so a terrain does not give it. numba's handling of inline overloads
is tuned for these (:func:`_tune_inlining`, numba internals): each call is
typed once per argument types, a body is never compiled on its own (the cold
compile of the enveloping trailer: +14 % without, +2 % with), and each copy of
a body gets its own variable names (numba's pedantic SSA check warned otherwise).

Python side, for the models' ``build`` functions (they receive the Python
ground object, e.g. :class:`~tyrelab.road.grid.RoadGrid`): :class:`Ground`;
the registry: :class:`TerrainKind`, :func:`register_terrain`,
:func:`terrain_kind`, :func:`terrain_names` (:mod:`.terrain_registry`,
re-exported here).
"""

from __future__ import annotations

import numba as nb
from numba.extending import overload

from .terrain_registry import (BUILTIN_TERRAIN, Ground, TerrainKind, block_maxima, element_shear,
                               profile_breaks, resolve_terrain,
                               register_terrain, rigid_contact, terrain_by_record, terrain_kind,
                               terrain_kinds, terrain_names, unit_friction)

#: the one door: the registry and Python side (:mod:`.terrain_registry`) and the compiled interface
__all__ = ["BUILTIN_TERRAIN", "Ground", "TerrainKind", "block_maxima", "element_shear", "profile_breaks",
           "resolve_terrain",
           "register_terrain", "rigid_contact", "terrain_by_record", "terrain_kind", "terrain_kinds",
           "terrain_names", "unit_friction", "terrain_height", "terrain_height_gradient",
           "terrain_penetration", "terrain_zmax", "terrain_range", "terrain_friction",
           "terrain_is_rigid", "terrain_contact", "terrain_shear", "terrain_lines", "terrain_row",
           "terrain_line_height", "terrain_row_height", "terrain_blocks", "terrain_block_max",
           "ground_range"]

# --- the compiled interface ------------------------------------------------------------
# Each function below is a stub for Python and an inline overload for numba: at compile
# time the overload looks the record's type up and returns a body that calls the
# registered function (module docstring: why inline).

def terrain_height(terrain, x, y):
    """Height [m] of the ground at (x, y)."""
    raise NotImplementedError("compiled only")


@overload(terrain_height, inline="always")
def _terrain_height(terrain, x, y):
    fn = terrain_by_record(terrain).height

    def impl(terrain, x, y):
        return fn(terrain, x, y)
    return impl


def terrain_height_gradient(terrain, x, y):
    """``(h, dh/dx, dh/dy)`` at (x, y)."""
    raise NotImplementedError("compiled only")


@overload(terrain_height_gradient, inline="always")
def _terrain_height_gradient(terrain, x, y):
    fn = terrain_by_record(terrain).height_gradient

    def impl(terrain, x, y):
        return fn(terrain, x, y)
    return impl


def terrain_penetration(terrain, x, y, z):
    """``(h - z, h, dh/dx, dh/dy)`` at (x, y); the gradient only where ``h > z`` (else 0):
    how deep a point at height z is in the ground, and the ground there."""
    raise NotImplementedError("compiled only")


@overload(terrain_penetration, inline="always")
def _terrain_penetration(terrain, x, y, z):
    fn = terrain_by_record(terrain).penetration

    def impl(terrain, x, y, z):
        return fn(terrain, x, y, z)
    return impl


def terrain_zmax(terrain, x0, x1):
    """An upper bound [m] of the ground over every y for x in [x0, x1]: ground no tyre
    part reaches above it is skipped."""
    raise NotImplementedError("compiled only")


@overload(terrain_zmax, inline="always")
def _terrain_zmax(terrain, x0, x1):
    fn = terrain_by_record(terrain).zmax

    def impl(terrain, x0, x1):
        return fn(terrain, x0, x1)
    return impl


def terrain_range(terrain):
    """``(zmin, zmax)``: bounds of the ground everywhere; equal only on one level plane."""
    raise NotImplementedError("compiled only")


@overload(terrain_range, inline="always")
def _terrain_range(terrain):
    fn = terrain_by_record(terrain).range

    def impl(terrain):
        return fn(terrain)
    return impl


def terrain_friction(terrain, x, y):
    """A scale [-] on the tyre's friction at (x, y) (1 on the rigid road)."""
    raise NotImplementedError("compiled only")


@overload(terrain_friction, inline="always")
def _terrain_friction(terrain, x, y):
    fn = terrain_by_record(terrain).friction

    def impl(terrain, x, y):
        return fn(terrain, x, y)
    return impl


def terrain_is_rigid(terrain):
    """True for a ground that never moves (a compile-time constant)."""
    raise NotImplementedError("compiled only")


@overload(terrain_is_rigid, inline="always")
def _terrain_is_rigid(terrain):
    rigid = terrain_by_record(terrain).rigid

    def impl(terrain):
        return rigid
    return impl


def terrain_contact(terrain, x, y, penetration, area, v1, v2, fn, f1, f2, dt):
    """The forces ``(fn, f1, f2)`` [N] the ground carries from a tyre element.

    The element, of contact ``area`` [m^2] (0: a point contact, the ground
    chooses), is at (x, y), ``penetration`` [m] below the ground's current
    surface, slides along it at ``(v1, v2)`` [m/s] (along the heading and
    across) and by the tyre's own law pushes with normal force ``fn`` and
    tangential forces ``f1, f2`` [N]. A deformable ground sinks under it
    (its state advanced by ``dt`` [s]) and returns what it carries; the
    rigid ground returns the forces unchanged. Called only where
    ``terrain_is_rigid`` is False.
    """
    raise NotImplementedError("compiled only")


@overload(terrain_contact, inline="always")
def _terrain_contact(terrain, x, y, penetration, area, v1, v2, fn, f1, f2, dt):
    contact = terrain_by_record(terrain).contact

    def impl(terrain, x, y, penetration, area, v1, v2, fn, f1, f2, dt):
        return contact(terrain, x, y, penetration, area, v1, v2, fn, f1, f2, dt)
    return impl


def terrain_shear(terrain, x, y, fn, area, m1, m2, d1, d2, element_stiffness, limit):
    """The ground's answer to a tyre element's shear: ``(own, f1, f2, m1, m2)``.

    The element at (x, y), carried by the ground with normal force ``fn`` [N] over its
    contact ``area`` [m^2], has slid ``(d1, d2)`` [m] over it in this step (along the
    heading and across) from the shear state ``(m1, m2)`` it kept from the last (0 on
    entering contact); ``element_stiffness`` its own shear stiffness per area [Pa/m],
    ``limit`` [N] its own friction's bound. A ground with a shear law of its own (the
    soil) returns ``own`` True, the tangential forces ``f1, f2`` [N] on the element and
    its new state; the others return ``own`` False, and the element's own law stands
    (the rigid ground's). Called only where ``terrain_is_rigid`` is False.
    """
    raise NotImplementedError("compiled only")


@overload(terrain_shear, inline="always")
def _terrain_shear(terrain, x, y, fn, area, m1, m2, d1, d2, element_stiffness, limit):
    shear = terrain_by_record(terrain).shear

    def impl(terrain, x, y, fn, area, m1, m2, d1, d2, element_stiffness, limit):
        return shear(terrain, x, y, fn, area, m1, m2, d1, d2, element_stiffness, limit)
    return impl


def terrain_lines(terrain):
    """``(x_first, spacing, inv_spacing, count)``: the break lines ``x_first + k spacing``,
    ``k = 0 .. count-1``, between which the height along x is linear (constant beyond
    the first and the last); ``inv_spacing`` is ``1 / spacing`` as the terrain rounds it."""
    raise NotImplementedError("compiled only")


@overload(terrain_lines, inline="always")
def _terrain_lines(terrain):
    fn = terrain_by_record(terrain).lines

    def impl(terrain):
        return fn(terrain)
    return impl


def terrain_row(terrain, y):
    """``(row, weight)``: the handle (int, float) of the line of constant y."""
    raise NotImplementedError("compiled only")


@overload(terrain_row, inline="always")
def _terrain_row(terrain, y):
    fn = terrain_by_record(terrain).row

    def impl(terrain, y):
        return fn(terrain, y)
    return impl


def terrain_line_height(terrain, row, weight, k):
    """Height [m] at break line k (``0 <= k < count``) on the line of handle (row, weight)."""
    raise NotImplementedError("compiled only")


@overload(terrain_line_height, inline="always")
def _terrain_line_height(terrain, row, weight, k):
    fn = terrain_by_record(terrain).line_height

    def impl(terrain, row, weight, k):
        return fn(terrain, row, weight, k)
    return impl


@nb.njit(cache=True, inline="always")
def terrain_row_height(terrain, row, weight, x):
    """Height [m] at any x on the line of handle (row, weight): from the break lines, between
    which the height along x is linear, and beyond which it is constant (derived from
    :func:`terrain_lines` and :func:`terrain_line_height`, so a terrain does not give it)."""
    line0, _, inv_spacing, count = terrain_lines(terrain)
    u = (x - line0) * inv_spacing
    if u <= 0.0 or u >= count - 1:
        return terrain_line_height(terrain, row, weight, 0 if u <= 0.0 else count - 1)
    i = min(int(u), count - 2)
    t = u - i
    return (terrain_line_height(terrain, row, weight, i) * (1.0 - t)
            + terrain_line_height(terrain, row, weight, i + 1) * t)


def terrain_blocks(terrain):
    """``(x_first, length, count)``: the blocks ``[x_first + i length, x_first + (i + 1)
    length]`` whose bounds :func:`terrain_zmax` is made of (the end blocks continue)."""
    raise NotImplementedError("compiled only")


@overload(terrain_blocks, inline="always")
def _terrain_blocks(terrain):
    fn = terrain_by_record(terrain).blocks

    def impl(terrain):
        return fn(terrain)
    return impl


def terrain_block_max(terrain, i):
    """An upper bound [m] of the ground over every y in block i (clamped to the blocks)."""
    raise NotImplementedError("compiled only")


@overload(terrain_block_max, inline="always")
def _terrain_block_max(terrain, i):
    fn = terrain_by_record(terrain).block_max

    def impl(terrain, i):
        return fn(terrain, i)
    return impl


def _tune_inlining(*stubs):
    """Tune numba's handling of the interface's inline overloads (module docstring).

    numba handles an inline overload with costs that buy nothing here: it
    compiles the body on its own (typing, lowering, LLVM) before inlining it,
    though only the caller's copy is ever used; and it types the body again from
    bytecode every time type inference meets the call, several times per call
    site, though the result depends only on the argument types and the compile's
    flags (the enveloping trailer's cold compile: +14 % over the direct calls
    with numba's handling, +2 % with this). For each stub's template (numba internals: its ``generic``,
    ``_get_jit_decorator`` and ``_inline_overloads``, pinned with the rest in
    ``core/jit_cache.TESTED_NUMBA``) the typing is kept per argument types and
    flags, the body's dispatcher may not compile (the inlining needs its typed
    IR only), and every inlined copy gets a fresh identity (:class:`_FreshInlines`).
    """
    from numba.core.targetconfig import ConfigStack
    from numba.core.typing.templates import builtin_registry

    for value, fnty in builtin_registry.globals:
        if not any(value is stub for stub in stubs):
            continue
        for template in fnty.templates:
            generic = template.generic
            typed = {}

            def once(self, args, kws, generic=generic, typed=typed):
                key = (self.context, tuple(args), tuple(sorted(kws.items())),
                       ConfigStack.top_or_none())
                if key not in typed:
                    typed[key] = generic(self, args, kws)
                return typed[key]
            template.generic = once
            template._get_jit_decorator = _typing_only(template._get_jit_decorator)
            template._inline_overloads = _FreshInlines(template._inline_overloads)


class _FreshInlines(dict):
    """A template's typed bodies, handed out under a new function identity at every
    call site they are inlined into (:func:`_tune_inlining`).

    numba names a body's variables in the caller after the body's identity; two
    copies of one body in one caller (local_zmax's, say, directly and through an
    inlined function) would share names, which numba renames behind its SSA
    check's back: a pedantic warning for every variable assigned twice, and IR
    that is right only because SSA keeps the names.
    """

    def __getitem__(self, key):
        entry = super().__getitem__(key)
        info = entry.get("iinfo")
        if info is None:
            return entry
        func_ir = info.func_ir.copy()
        func_ir.func_id = func_ir.func_id.derive()
        return {**entry, "iinfo": info._replace(func_ir=func_ir)}


def _typing_only(get_jit_decorator):
    """A template's jit decorator whose dispatchers never compile (:func:`_tune_inlining`)."""
    def get(self):
        jitter = get_jit_decorator(self)

        def make(**options):
            decorate = jitter(**options)

            def wrap(pyfunc):
                dispatcher = decorate(pyfunc)
                dispatcher._can_compile = False  # (disable_compile() wants a signature first)
                return dispatcher
            return wrap
        return make
    return get


_tune_inlining(terrain_height, terrain_height_gradient, terrain_penetration, terrain_zmax,
           terrain_range, terrain_friction, terrain_is_rigid, terrain_contact, terrain_shear,
           terrain_lines,
           terrain_row, terrain_line_height, terrain_blocks, terrain_block_max)


@nb.njit(cache=True)
def ground_range(terrain):
    """:func:`terrain_range` of any registered terrain record, callable from Python."""
    return terrain_range(terrain)
