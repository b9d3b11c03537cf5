"""The one table of a run's outputs: the output groups a scene asks for, the arrays the runs record per saved step,
and every variable of the result Dataset with its dimensions, units, long name and the quantity it is computed
from.

The table drives everything downstream: the scene validates ``outputs.variables`` against :data:`GROUPS`; the
fixed-step runs allocate and record the :data:`CHANNELS` the asked-for groups read (the others get a one-row
scratch array); the result builder (``wecss.sim``) makes each :data:`VARIABLES` row of the asked-for groups from
its quantity, streamed part by part where the group allows; ``wecss.attributes`` takes units and long names from
here. Adding a variable is a row here and the code that computes its quantity (a function of the same name in
``wecss.sim``'s quantities, which a test holds to this table); adding a recorded array is a :class:`Channel` row and
the kernels' line that fills it.

Dimensions ``dof_linear``, ``dof_angular``, ``dof_generalised`` split the generalised coordinates by kind (a
translation [m], a rotation [rad], a body's generalised mode [1]); ``hydro_dof_*`` split the hydrodynamic DOFs the
same way; a per-PTO variable has the one ``pto`` dimension and comes per PTO kind (NaN for the PTOs of the other
kind), so that no variable ever mixes units.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from .constants import DOF_KINDS

PTO_KINDS: tuple[str, ...] = ("rotary", "linear")
"""The kinds of a PTO: on a revolute joint (torque [N m], stroke [rad]) or linear (force [N], stroke [m])."""


@dataclass(frozen=True)
class Group:
    """An output group a scene may ask for (``outputs.variables``).

    Attributes
    ----------
    name : str
    description : str
    default : bool
        In the default outputs.
    streamed : bool
        A streamed run (``simulate(scene, path=...)``) writes its variables part by part; False: the group needs
        the whole record (the run is built whole, then written).
    needs : str or None
        The runner capability (an attribute of ``wecss.scene.Capabilities``) a runner must have to fill the group;
        None: every runner fills it.
    """

    name: str
    description: str
    default: bool = True
    streamed: bool = True
    needs: str | None = None


GROUPS: tuple[Group, ...] = (
    Group("motion", "generalised coordinates, velocities and accelerations"),
    Group("pto", "PTO strokes, rates, forces and absorbed power"),
    Group("excitation", "wave excitation on the hydrodynamic DOFs"),
    Group("radiation", "radiation memory force and the hydrodynamic DOFs' velocities", default=False),
    Group("elevation", "undisturbed wave elevation at the origin and at the scene's probes (outputs.probes)"),
    Group("poses", "bodies' centre-of-mass positions and rotation vectors"),
    Group(
        "loads",
        "joint reactions, PTO end loads, section loads and hot-spot stresses of the device's members, recovered from "
        "the record after the run (with amplitudes per wave frequency in frequency-domain runs), and the stress field "
        "and fatigue life at every fibre point of a frozen flexible body",
        default=False,
        streamed=False,
    ),
    Group(
        "hydrodynamics",
        "the forces beyond the linear hydrodynamics the scene switches on ([hydrodynamics]): body-exact hydrostatics "
        "and Froude-Krylov, viscous drag, Morison inertia, and their sum added to the linear forces",
        default=False,
        needs="terms",
    ),
)

GROUP_NAMES: tuple[str, ...] = tuple(g.name for g in GROUPS)
DEFAULT_GROUPS: tuple[str, ...] = tuple(g.name for g in GROUPS if g.default)
STREAMED_GROUPS: tuple[str, ...] = tuple(g.name for g in GROUPS if g.streamed)


@dataclass(frozen=True)
class Channel:
    """An array the runs record at every saved step (one row per saved step, ``size`` columns).

    Attributes
    ----------
    name : str
        Its key in a record (``Record.series[name]``).
    size : str
        Its columns: "nq" (configuration coordinates), "nv" (generalised velocities), "n_pto", "n_h" (hydrodynamic
        DOFs, stored translations first: ``Record.hydro_order``), "n_terms" (per body, each term's force and
        moment).
    description : str
    groups : tuple of str
        The output groups that read it; a run whose groups read none keeps a one-row scratch array.
    kept : bool
        Kept whatever the groups (the result's notes on the motion read it).
    """

    name: str
    size: str
    description: str
    groups: tuple[str, ...] = ()
    kept: bool = False


CHANNELS: tuple[Channel, ...] = (
    Channel("q", "nq", "configuration", kept=True),
    Channel("v", "nv", "generalised velocities", kept=True),
    Channel("a", "nv", "generalised accelerations", ("motion", "loads")),
    Channel("x", "n_pto", "PTO strokes from rest", ("pto", "loads")),
    Channel("xd", "n_pto", "PTO stroke rates", ("pto", "loads")),
    Channel("f", "n_pto", "PTO forces (controller, saturated, and device spring)", ("pto", "loads")),
    Channel("rad", "n_h", "radiation memory force on the hydrodynamic DOFs", ("radiation", "loads")),
    Channel("exc", "n_h", "excitation on the hydrodynamic DOFs", ("excitation", "loads")),
    Channel(
        "terms",
        "n_terms",
        "the hydrodynamic terms' forces and moments per body (wecss.compiled._viscous.TERM_ROWS), world axes",
        ("hydrodynamics",),
    ),
    Channel("p", "n_pto", "absorbed PTO power over the step ending here (the recorder's, from the work)", ("pto",)),
)
"""The recorded arrays, in the order the fixed-step kernels hand them to the recorder; the last, ``p``, the recorder
makes itself: the absorbed PTO power of the step that ends at the saved step, the work
of a sampled controller's force held over the step divided by the step (exact for a held force), or for a
continuous force law (linear gains) its power at the step's end (the quadrature of the runs' statistics)."""

CHANNEL_NAMES: tuple[str, ...] = tuple(c.name for c in CHANNELS)


@dataclass(frozen=True)
class Variable:
    """A variable of the result Dataset.

    Attributes
    ----------
    name : str
    group : str
        Its output group, or "statistics" (always present).
    dims : tuple of str
    long_name, units : str
    quantity : str
        The quantity its values come from (a function of that name in ``wecss.sim``'s quantities: a per-step
        array for time series, a per-PTO array for statistics).
    kind : str or None
        The columns of the quantity it keeps: for a variable over the ``pto`` dimension a PTO kind ("rotary",
        "linear": every PTO, NaN for the other kind; absent when no PTO is of this kind), else a DOF kind
        ("linear", "angular", "generalised": the columns of that kind, on the kind's dimension, the second; absent
        when there are none). None: all of it.
    spectral : bool
        Frequency-domain runs also give ``<name>_equilibrium`` (without the ``time`` dimension) and
        ``<name>_amplitude`` (per wave frequency ``omega``).
    """

    name: str
    group: str
    dims: tuple[str, ...]
    long_name: str
    units: str
    quantity: str
    kind: str | None = None
    spectral: bool = False


def _by_dof_kind(
    group: str, quantity: str, names: tuple[str, str, str], long_names: tuple[str, str, str], units: tuple[str, ...]
) -> tuple[Variable, ...]:
    """One time series per generalised-coordinate kind (translations, rotations, generalised modes)."""
    dims = ("dof_linear", "dof_angular", "dof_generalised")
    return tuple(
        Variable(name, group, ("time", dim), long, unit, quantity, kind)
        for name, long, unit, dim, kind in zip(names, long_names, units, dims, DOF_KINDS, strict=True)
    )


def _by_hydro_kind(
    group: str, quantity: str, names: tuple[str, str, str], long_names: tuple[str, str, str], units: tuple[str, ...]
) -> tuple[Variable, ...]:
    """One time series per kind of hydrodynamic DOF."""
    dims = ("hydro_dof_linear", "hydro_dof_angular", "hydro_dof_generalised")
    return tuple(
        Variable(name, group, ("time", dim), long, unit, quantity, kind)
        for name, long, unit, dim, kind in zip(names, long_names, units, dims, DOF_KINDS, strict=True)
    )


def _by_pto_kind(
    group: str, quantity: str, names: tuple[str, str], long_names: tuple[str, str], units: tuple[str, str], dims
) -> tuple[Variable, ...]:
    """One variable per PTO kind over the ``pto`` dimension (NaN for the other kind)."""
    return tuple(
        Variable(name, group, dims, long, unit, quantity, kind)
        for name, long, unit, kind in zip(names, long_names, units, PTO_KINDS, strict=True)
    )


_LOADS = "loads"
_JOINT = ("joint", "axis")
_PTO_END = ("pto", "pto_end", "axis")
_SPOT = ("hot_spot", "section_axis")

VARIABLES: tuple[Variable, ...] = (
    *_by_dof_kind(
        "motion",
        "coordinates",
        ("displacement", "angle", "generalised_coordinate"),
        (
            "translational generalised coordinate",
            "rotational generalised coordinate",
            "coordinate of a body's generalised mode",
        ),
        ("m", "rad", "1"),
    ),
    *_by_dof_kind(
        "motion",
        "velocities",
        ("velocity", "angular_velocity", "generalised_velocity"),
        (
            "translational generalised velocity",
            "rotational generalised velocity",
            "rate of a body's generalised mode",
        ),
        ("m/s", "rad/s", "1/s"),
    ),
    *_by_dof_kind(
        "motion",
        "accelerations",
        ("acceleration", "angular_acceleration", "generalised_acceleration"),
        (
            "translational generalised acceleration",
            "rotational generalised acceleration",
            "acceleration of a body's generalised mode",
        ),
        ("m/s^2", "rad/s^2", "1/s^2"),
    ),
    *_by_pto_kind(
        "pto",
        "pto_stroke",
        ("pto_angle", "pto_displacement"),
        (
            "rotary PTO stroke: joint angle from the spring's rest angle (NaN for linear PTOs)",
            "linear PTO stroke from the rest length (NaN for rotary PTOs)",
        ),
        ("rad", "m"),
        ("time", "pto"),
    ),
    *_by_pto_kind(
        "pto",
        "pto_rate",
        ("pto_angular_velocity", "pto_velocity"),
        ("rotary PTO stroke rate (NaN for linear PTOs)", "linear PTO stroke rate (NaN for rotary PTOs)"),
        ("rad/s", "m/s"),
        ("time", "pto"),
    ),
    *_by_pto_kind(
        "pto",
        "pto_force",
        ("pto_torque", "pto_force"),
        (
            "rotary PTO torque (spring, controller), positive driving the angle up (NaN for linear PTOs)",
            "linear PTO force (spring, controller), positive extending (NaN for rotary PTOs)",
        ),
        ("N m", "N"),
        ("time", "pto"),
    ),
    Variable(
        "pto_power",
        "pto",
        ("time", "pto"),
        "power absorbed by the PTO over the step ending here: a held controller force's work over the step / step; "
        "-(force - device spring force) * stroke rate for linear gains",
        "W",
        "pto_power",
    ),
    *_by_hydro_kind(
        "excitation",
        "excitation",
        ("excitation_force", "excitation_moment", "excitation_generalised_force"),
        (
            "wave excitation force, world axes",
            "wave excitation moment about the centre of mass, world axes",
            "wave excitation on a generalised mode (work per unit coordinate)",
        ),
        ("N", "N m", "J"),
    ),
    *_by_hydro_kind(
        "radiation",
        "radiation",
        ("radiation_force", "radiation_moment", "radiation_generalised_force"),
        (
            "radiation memory force (without the A_inf part), world axes",
            "radiation memory moment (without the A_inf part), world axes",
            "radiation memory force on a generalised mode (without the A_inf part)",
        ),
        ("N", "N m", "J"),
    ),
    *_by_hydro_kind(
        "radiation",
        "hydro_velocity",
        ("hydro_velocity", "hydro_angular_velocity", "hydro_generalised_velocity"),
        (
            "velocity of the centre of mass, world axes",
            "angular velocity, world axes",
            "rate of a generalised mode of the hydrodynamic database",
        ),
        ("m/s", "rad/s", "1/s"),
    ),
    Variable(
        "wave_elevation",
        "elevation",
        ("time",),
        "undisturbed wave elevation at the origin, as applied (with the start ramp)",
        "m",
        "elevation",
    ),
    Variable(
        "wave_elevation_probe",
        "elevation",
        ("time", "probe"),
        "undisturbed wave elevation at the scene's probes (outputs.probes), as applied (with the start ramp)",
        "m",
        "elevation_probe",
    ),
    Variable(
        "body_position",
        "poses",
        ("time", "body", "axis"),
        "position of the body's centre of mass, world frame",
        "m",
        "body_position",
    ),
    Variable(
        "body_rotation",
        "poses",
        ("time", "body", "axis"),
        "rotation vector of the body from its reference orientation",
        "rad",
        "body_rotation",
    ),
    Variable(
        "joint_reaction_force",
        _LOADS,
        ("time", *_JOINT),
        "reaction force of the joint on its child's subtree, world axes",
        "N",
        "joint_force",
        spectral=True,
    ),
    Variable(
        "joint_reaction_moment",
        _LOADS,
        ("time", *_JOINT),
        "reaction moment of the joint on its child's subtree about the joint point, world axes",
        "N m",
        "joint_moment",
        spectral=True,
    ),
    Variable(
        "joint_reaction_force_local",
        _LOADS,
        ("time", *_JOINT),
        "joint reaction force, axes of the child body",
        "N",
        "joint_force_local",
        spectral=True,
    ),
    Variable(
        "joint_reaction_moment_local",
        _LOADS,
        ("time", *_JOINT),
        "joint reaction moment, axes of the child body",
        "N m",
        "joint_moment_local",
        spectral=True,
    ),
    Variable(
        "pto_end_force",
        _LOADS,
        ("time", *_PTO_END),
        "PTO force on the body at each end, at the attachment, world axes",
        "N",
        "pto_end_force",
        spectral=True,
    ),
    Variable(
        "pto_end_moment",
        _LOADS,
        ("time", *_PTO_END),
        "PTO moment (joint PTO torque) on the body at each end, world axes",
        "N m",
        "pto_end_moment",
        spectral=True,
    ),
    Variable(
        "section_force",
        _LOADS,
        ("time", *_SPOT),
        "section force at the hot spot's station (N along x, shears Vy, Vz), member axes",
        "N",
        "section_force",
        spectral=True,
    ),
    Variable(
        "section_moment",
        _LOADS,
        ("time", *_SPOT),
        "section moment at the hot spot's station about the section centre (T, My, Mz), member axes",
        "N m",
        "section_moment",
        spectral=True,
    ),
    *(
        Variable(f"{kind}_stress", _LOADS, ("time", "hot_spot"), long, "Pa", f"{kind}_stress", spectral=True)
        for kind, long in (
            ("axial", "axial stress N/A at the hot spot, times its SCF (tension positive)"),
            ("bending", "bending stress My z/Iy - Mz y/Iz at the hot spot, times its SCF"),
            ("normal", "normal stress (axial plus bending) at the hot spot, times its SCF"),
            ("shear", "torsional shear stress T/W_t at the hot spot, times its SCF"),
            ("von_mises", "von Mises stress at the hot spot"),
            (
                "signed_von_mises",
                "signed von Mises stress at the hot spot: the sign of the largest principal stress (Eq. 53)",
            ),
        )
    ),
    *(
        Variable(f"fibre_{name}", _LOADS, ("fibre_point",), long, unit, f"fibre_{name}")
        for name, long, unit in (
            (
                "life",
                "fatigue life at the point from its signed von Mises stress over the statistics window (rainflow, "
                "Miner, paper 003 Eq. 55 and its Table 5 S-N curve; inf where nothing was counted)",
                "year",
            ),
            ("damage", "Miner damage of the statistics window at the point", "1"),
            ("stress_max", "largest signed von Mises stress at the point over the statistics window", "Pa"),
            ("stress_min", "smallest signed von Mises stress at the point over the statistics window", "Pa"),
            ("stress_rms", "RMS of the von Mises stress at the point over the statistics window", "Pa"),
        )
    ),
    *(
        Variable(f"{term}_{part}", "hydrodynamics", ("time", "body", "axis"), f"{long}, {what}", unit, f"{term}_{part}")
        for term, long in (
            ("hydrostatic", "body-exact hydrostatic pressure force on the mesh below the free surface (whole)"),
            ("froude_krylov", "body-exact Froude-Krylov force on the mesh below the free surface (whole)"),
            ("viscous", "viscous force: body drag, linear damping and Morison drag"),
            ("morison_inertia", "fluid inertia force on the Morison elements"),
            ("nonlinear_hydro", "hydrodynamic force added to the linear model's (remainder, drag, Morison)"),
        )
        for part, what, unit in (
            ("force", "world axes", "N"),
            ("moment", "about the centre of mass, world axes", "N m"),
        )
    ),
    Variable(
        "mean_pto_power",
        "statistics",
        ("pto",),
        "mean absorbed PTO power over the statistics window",
        "W",
        "mean_power",
    ),
    Variable(
        "force_limit_time",
        "statistics",
        ("pto",),
        "time the controller's force was saturated at the PTO's force limit",
        "s",
        "force_limit_time",
    ),
    Variable(
        "force_limit_episodes",
        "statistics",
        ("pto",),
        "times the controller's force reached the PTO's force limit",
        "1",
        "force_limit_episodes",
    ),
    Variable(
        "stroke_limit_time",
        "statistics",
        ("pto",),
        "time the PTO stroke was beyond its limit (end stop engaged)",
        "s",
        "stroke_limit_time",
    ),
    Variable(
        "stroke_limit_episodes",
        "statistics",
        ("pto",),
        "times the PTO stroke passed its limit (end stop engaged)",
        "1",
        "stroke_limit_episodes",
    ),
    *_by_pto_kind(
        "statistics",
        "rms_stroke",
        ("rms_pto_angle", "rms_pto_displacement"),
        (
            "RMS rotary PTO angle about its mean over the statistics window (NaN for linear PTOs)",
            "RMS linear PTO stroke about its mean over the statistics window (NaN for rotary PTOs)",
        ),
        ("rad", "m"),
        ("pto",),
    ),
    Variable(
        "power_bound",
        "statistics",
        ("pto",),
        "complex-conjugate bound of mean absorbed power over the statistics window, on the run's wave record "
        "(linear, unconstrained, steady state)",
        "W",
        "power_bound",
    ),
    Variable(
        "power_bound_spectral",
        "statistics",
        ("pto",),
        "complex-conjugate bound of mean absorbed power, spectral expectation over the wave components "
        "(linear, unconstrained)",
        "W",
        "power_bound_spectral",
    ),
)
"""Every variable of a result Dataset, in the order they are added."""

COORDINATE_ATTRS: Mapping[str, Mapping[str, str]] = {
    "time": {"long_name": "time", "standard_name": "time", "units": "s"},
    "dof_linear": {"long_name": "translational generalised coordinate (joint__label)"},
    "dof_angular": {"long_name": "rotational generalised coordinate (joint__label)"},
    "dof_generalised": {"long_name": "generalised coordinate of a body's generalised mode (body__mode)"},
    "pto": {"long_name": "power take-off (in the device spec's order)"},
    "pto_kind": {"long_name": "kind of power take-off: rotary (on a revolute joint) or linear (prismatic or actuator)"},
    "hydro_dof_linear": {"long_name": "translational degree of freedom of the hydrodynamic database (body__Dof)"},
    "hydro_dof_angular": {"long_name": "rotational degree of freedom of the hydrodynamic database (body__Dof)"},
    "hydro_dof_generalised": {"long_name": "generalised mode of the hydrodynamic database (body__mode)"},
    "hot_spot": {"long_name": "hot spot of a beam member (member.spot)"},
    "fibre_point": {
        "long_name": "stress point of a frozen flexible body's structure, quasi-static (member.spot, or "
        "member@station.fibreK at every node)"
    },
    "section_axis": {"long_name": "member axes: x along the member from start to end, z up across it"},
}
"""Attributes of the result's own coordinates (``body``, ``axis`` and ``omega`` are shared with the hydrodynamic
databases: ``wecss.attributes``)."""


def _check_table() -> None:
    """The table's own consistency (run at import: a malformed row fails at once, with its name)."""
    groups = {*GROUP_NAMES, "statistics"}
    names = [v.name for v in VARIABLES]
    if len(set(names)) != len(names):
        raise RuntimeError(
            f"wecss.outputs: duplicate variable names {sorted({n for n in names if names.count(n) > 1})}"
        )
    for v in VARIABLES:
        if v.group not in groups:
            raise RuntimeError(f"wecss.outputs: variable {v.name!r} in unknown group {v.group!r}")
        kinds = PTO_KINDS if "pto" in v.dims else DOF_KINDS
        if v.kind is not None and v.kind not in kinds:
            raise RuntimeError(f"wecss.outputs: variable {v.name!r} has kind {v.kind!r}; accepted {kinds}")
    for c in CHANNELS:
        unknown = set(c.groups) - set(GROUP_NAMES)
        if unknown:
            raise RuntimeError(f"wecss.outputs: channel {c.name!r} read by unknown groups {sorted(unknown)}")


_check_table()


def variables_of(groups: tuple[str, ...] | set[str]) -> tuple[Variable, ...]:
    """The table's variables of the given groups (the statistics always), in table order."""
    return tuple(v for v in VARIABLES if v.group in groups or v.group == "statistics")


def variable_attrs() -> dict[str, dict[str, str]]:
    """``long_name`` and ``units`` of every variable and result coordinate in the table."""
    out = {name: dict(attrs) for name, attrs in COORDINATE_ATTRS.items()}
    for v in VARIABLES:
        out[v.name] = {"long_name": v.long_name, "units": v.units}
    return out
