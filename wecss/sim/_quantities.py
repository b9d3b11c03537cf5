"""The quantities the output table's variables are made of (``wecss.outputs.Variable.quantity``), each computed
from a run's :class:`Record` by the function of the same name in :data:`QUANTITIES`.

A time-series quantity is an array with one row per saved step (its columns split by the table's ``kind``); a
statistic is one value per PTO; a load is a field of the loads recovered from the record (``wecss.sim._loads``).
A function returns None where the quantity does not exist for this device or run (no PTO of a kind, no members,
no power bound): its variables are then absent. A test holds this table to ``wecss.outputs``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..compiled import TERM_ROWS
from ..compiled.kernels import hydro_velocity, poses
from ..control import ControlledScene
from ..control.design import PowerBound, power_bound
from ..multibody import difference
from ..waves import Ramp
from ._bound_window import window_bound
from ._fibre_field import FibreField, fibre_field
from ._layout import natural_hydro_order
from ._load_amplitudes import load_amplitudes
from ._loads import Loads, field_bodies, recover_loads
from ._record import Record, stats_start
from ._sections import hot_spot_stresses


@dataclass
class Quantities:
    """The quantities of one record, each computed once on first use (:meth:`get`).

    ``elevation``, ``elevation_probe``: the ``elevation`` and ``elevation_probe`` quantities at ``record.time`` when
    the caller has them (a streamed run evaluates the whole run's once). ``notes`` collects what a quantity has to
    say (a power bound that could not be had).
    """

    controlled: ControlledScene
    record: Record
    elevation: np.ndarray | None = None
    notes: list[str] = field(default_factory=list)
    elevation_probe: np.ndarray | None = None
    _values: dict[str, Any] = field(default_factory=dict)

    @property
    def stored_hydro(self) -> np.ndarray:
        """The hydro DOFs of the record's ``rad`` and ``exc`` columns, as indices into the database's."""
        record = self.record
        return natural_hydro_order(self.controlled) if record.hydro_order is None else record.hydro_order

    def hydro_columns(self, values: np.ndarray) -> np.ndarray:
        """``values`` on the hydro DOFs (database order when the record has no ``hydro_order``) in the stored order
        (a view when the record stores them so already)."""
        return values[:, self.stored_hydro] if self.record.hydro_order is None else values

    def get(self, name: str) -> Any:
        """The quantity ``name`` (None where it does not exist)."""
        if name not in self._values:
            self._values[name] = QUANTITIES[name](self)
        return self._values[name]

    def spectral(self, name: str) -> tuple[np.ndarray | None, np.ndarray | None]:
        """The load quantity ``name`` at the equilibrium and as complex amplitudes per wave frequency (a
        frequency-domain run; each None where it does not exist: the von Mises stresses have no amplitudes)."""
        both = self.get("spectral_loads")
        if both is None:
            return None, None
        equilibrium, amplitudes = (LOAD_PICKS[name](self, loads) for loads in both)
        return equilibrium, amplitudes


def _coordinates(qs: Quantities) -> np.ndarray:
    """Generalised coordinates as velocity-space values (a free base: its CoM position and rotation vector)."""
    q = qs.record["q"]
    model = qs.controlled.device.model
    if model.nq == model.nv:
        return q
    neutral = model.neutral_configuration()
    return np.array([difference(model, neutral, row) for row in q])


def _has_ptos(qs: Quantities) -> bool:
    return bool(qs.controlled.device.ptos)


def _pto_power(qs: Quantities) -> np.ndarray | None:
    """Absorbed power of the step ending at each saved step, as the run recorded it (the channel ``p``: the work of
    a sampled controller's held force over the step, or a continuous force law's power; the device spring's force
    -k x is conservative and left out)."""
    return qs.record["p"] if _has_ptos(qs) else None


def _hydro_velocity(qs: Quantities) -> np.ndarray:
    r, p = qs.record, qs.controlled.plant
    u = np.array([hydro_velocity(p, q, v) for q, v in zip(r["q"], r["v"], strict=True)])
    return u[:, qs.stored_hydro] if u.size else np.zeros((0, qs.stored_hydro.size))


def elevation_series(controlled: ControlledScene, time: np.ndarray) -> np.ndarray:
    """The undisturbed elevation at ``time`` [m] as the run applied it (with the start ramp; the frequency domain
    has none). Its evaluation depends on the whole of ``time`` (one FFT where the record is periodic, else a
    recurrence): to round-off, and exactly when evaluated on the same times."""
    scene = controlled.scene
    eta = controlled.waves.elevation(time) if controlled.waves is not None else np.zeros(time.size)
    if scene.sea.ramp_s > 0 and scene.runner.capabilities.transient:  # as applied: with the start ramp
        eta = eta * Ramp(scene.sea.ramp_s)(time)
    return eta


def _elevation(qs: Quantities) -> np.ndarray:
    return elevation_series(qs.controlled, qs.record.time) if qs.elevation is None else qs.elevation


def probe_series(controlled: ControlledScene, time: np.ndarray) -> np.ndarray | None:
    """The undisturbed elevation at the scene's probes (``outputs.probes``) at ``time`` (n_times, n_probes) [m], as
    the run applied it (with the start ramp), each probe evaluated as :func:`elevation_series` evaluates the origin
    (so a probe at the origin equals it); None without probes."""
    scene = controlled.scene
    probes = scene.outputs.probe_points
    if not probes:
        return None
    out = np.zeros((time.size, len(probes)))
    waves = controlled.waves
    if waves is not None:
        depth, g = controlled.hydro.water_depth, controlled.hydro.g
        for j, (x, y) in enumerate(probes):
            out[:, j] = waves.elevation_at(time, x, y, depth, g)
    if scene.sea.ramp_s > 0 and scene.runner.capabilities.transient:
        out *= Ramp(scene.sea.ramp_s)(time)[:, None]
    return out


def _poses(qs: Quantities) -> tuple[np.ndarray, np.ndarray]:
    return poses(qs.controlled.plant, np.ascontiguousarray(qs.record["q"]))


def _loads(qs: Quantities) -> Loads:
    r = qs.record
    hydro = r["rad"] + r["exc"]
    if r.hydro_order is not None:  # back to the database's order
        hydro = hydro[:, np.argsort(r.hydro_order)]
    return recover_loads(qs.controlled, r["q"], r["v"], r["a"], (r["x"], r["xd"], r["f"]), hydro)


def _fibre_field(qs: Quantities) -> FibreField:
    """The stress field of the device's elastic bodies and frozen dry flexible bodies over the statistics window of
    the saved steps (``wecss.sim._fibre_field``)."""
    loads: Loads = qs.get("loads")
    controlled = qs.controlled
    model = controlled.device.model
    time = qs.record.time
    bodies = [
        (controlled.device.flexible_body(model.body_names[i]), loads.elastic.get(i, loads.histories[i]))
        for i in field_bodies(controlled)
        if i in loads.histories
    ]
    n = time.size  # saved rows: the start and every step (``field_bodies`` asks for every step)
    start = (
        stats_start(controlled)
        if n == controlled.n_steps + 1
        else n - max(1, round(controlled.scene.outputs.window * (n - 1)))
    )
    return fibre_field(bodies, float(time[1] - time[0]) if n > 1 else 1.0, start)


def _fibre(values: Callable[[FibreField], np.ndarray]) -> Callable[[Quantities], np.ndarray | None]:
    def quantity(qs: Quantities) -> np.ndarray | None:
        field = qs.get("fibre_field")
        return values(field) if field.names else None

    return quantity


def _spectral_loads(qs: Quantities) -> tuple[Loads, Loads] | None:
    """The equilibrium loads and their complex amplitudes per wave frequency of a frequency-domain run."""
    spectral = qs.record.spectral
    if spectral is None or not spectral.omega.size:
        return None
    return load_amplitudes(qs.controlled, spectral)


LoadPick = Callable[["Quantities", Loads], "np.ndarray | None"]
"""A load quantity from recovered loads (the run's, or the equilibrium's and the amplitudes' of a
frequency-domain run): None where the device has no such load."""


def _pto_end(values: Callable[[Loads], np.ndarray]) -> LoadPick:
    return lambda qs, loads: values(loads) if qs.controlled.device.ptos else None


def _section(values: Callable[[Loads], np.ndarray]) -> LoadPick:
    return lambda qs, loads: values(loads) if loads.section.shape[1] else None


def _stress(kind: str) -> LoadPick:
    def pick(qs: Quantities, loads: Loads) -> np.ndarray | None:
        if not loads.section.shape[1]:
            return None
        key = f"stresses of {id(loads)}"  # the six kinds of one set of loads are computed together
        if key not in qs._values:
            qs._values[key] = hot_spot_stresses(qs.controlled.device.members, loads.section)
        return qs._values[key].get(kind)  # complex amplitudes have the linear stresses only

    return pick


LOAD_PICKS: dict[str, LoadPick] = {
    "joint_force": lambda qs, loads: loads.joint_force,
    "joint_moment": lambda qs, loads: loads.joint_moment,
    "joint_force_local": lambda qs, loads: loads.joint_force_local,
    "joint_moment_local": lambda qs, loads: loads.joint_moment_local,
    "pto_end_force": _pto_end(lambda loads: loads.pto_body_force),
    "pto_end_moment": _pto_end(lambda loads: loads.pto_body_moment),
    "section_force": _section(lambda loads: loads.section[..., :3]),
    "section_moment": _section(lambda loads: loads.section[..., 3:]),
    **{
        f"{kind}_stress": _stress(kind)
        for kind in ("axial", "bending", "normal", "shear", "von_mises", "signed_von_mises")
    },
}
"""The load quantities (``loads`` group) by name."""


def _terms(qs: Quantities) -> np.ndarray:
    """The hydrodynamic terms' forces and moments (n_t, n_body, len(TERM_ROWS), 6), world axes."""
    values = qs.record["terms"]
    return values.reshape(values.shape[0], -1, len(TERM_ROWS), 6)


def _term(rows: tuple[str, ...], moment: bool) -> Callable[[Quantities], np.ndarray]:
    """The sum of the terms ``rows`` (their force, or their moment about the centre of mass) per body."""
    index = [TERM_ROWS.index(row) for row in rows]
    part = slice(3, 6) if moment else slice(0, 3)

    def quantity(qs: Quantities) -> np.ndarray:
        terms = qs.get("terms")
        return terms[:, :, index[0], part] if len(index) == 1 else terms[:, :, index, part].sum(axis=2)

    return quantity


_TERM_QUANTITIES = {
    "hydrostatic": ("hydrostatic",),
    "froude_krylov": ("froude_krylov",),
    "viscous": ("drag",),
    "morison_inertia": ("morison_inertia",),
    "nonlinear_hydro": ("remainder", "drag", "morison_inertia"),
}
"""The hydrodynamics group's quantities and the terms they sum."""


def _window_count(qs: Quantities) -> float:
    stats = qs.record.stats
    return max(1.0, float(stats[2, 0])) if stats.size else 1.0


def _mean_power(qs: Quantities) -> np.ndarray | None:
    return qs.record.stats[0] / _window_count(qs) if _has_ptos(qs) else None


def _rms_stroke(qs: Quantities) -> np.ndarray | None:
    """RMS stroke about the window's mean (as the metric)."""
    if not _has_ptos(qs):
        return None
    stats, count = qs.record.stats, _window_count(qs)
    mean = stats[3] / count
    return np.sqrt(np.maximum(stats[1] / count - mean**2, 0.0))


def _limit(row: int, seconds: bool) -> Callable[[Quantities], np.ndarray | None]:
    def quantity(qs: Quantities) -> np.ndarray | None:
        limits = qs.record.limits
        if not _has_ptos(qs) or limits is None:
            return None
        return limits[row] * qs.controlled.dt if seconds else limits[row]

    return quantity


def power_bound_of(controlled: ControlledScene) -> PowerBound:
    """The complex-conjugate bound of the scene's wave components on its open plant (the exact frequency-domain
    model; ``wecss.control.design.power_bound``), which every result in waves reports with its share of it."""
    exc = controlled.excitation
    if exc is None:
        raise ValueError("calm water has no power bound")
    return power_bound(controlled.control_context.linear_model(), exc.omega, exc.coefficients)


def _bound(qs: Quantities) -> PowerBound | None:
    """The complex-conjugate bound (None in calm water, without PTOs, or where it cannot be had: said in the
    notes)."""
    controlled = qs.controlled
    if not _has_ptos(qs) or controlled.excitation is None or not controlled.excitation.omega.size:
        return None
    try:
        return power_bound_of(controlled)
    except ValueError as err:  # a reported quantity: the run stands without it, and says why
        qs.notes.append(f"no complex-conjugate power bound: {err}")
        return None


def _power_bound(qs: Quantities) -> np.ndarray | None:
    """The bound per PTO of the excitation over the run's statistics window (``window_bound``)."""
    if qs.get("bound") is None:
        return None
    try:
        return window_bound(qs.controlled).per_pto
    except ValueError as err:
        qs.notes.append(f"no complex-conjugate power bound over the statistics window: {err}")
        return None


def _power_bound_spectral(qs: Quantities) -> np.ndarray | None:
    """The bound's spectral expectation per PTO (the sum over components)."""
    bound = qs.get("bound")
    return None if bound is None else bound.per_pto


QUANTITIES: dict[str, Callable[[Quantities], Any]] = {
    "coordinates": _coordinates,
    "velocities": lambda qs: qs.record["v"],
    "accelerations": lambda qs: qs.record["a"],
    "pto_stroke": lambda qs: qs.record["x"] if _has_ptos(qs) else None,
    "pto_rate": lambda qs: qs.record["xd"] if _has_ptos(qs) else None,
    "pto_force": lambda qs: qs.record["f"] if _has_ptos(qs) else None,
    "pto_power": _pto_power,
    "excitation": lambda qs: qs.hydro_columns(qs.record["exc"]),
    "radiation": lambda qs: qs.hydro_columns(qs.record["rad"]),
    "hydro_velocity": _hydro_velocity,
    "elevation": _elevation,
    "elevation_probe": lambda qs: (
        probe_series(qs.controlled, qs.record.time) if qs.elevation_probe is None else qs.elevation_probe
    ),
    "poses": _poses,
    "body_position": lambda qs: qs.get("poses")[0],
    "body_rotation": lambda qs: qs.get("poses")[1],
    "loads": _loads,
    "fibre_field": _fibre_field,
    "fibre_life": _fibre(lambda f: f.life),
    "fibre_damage": _fibre(lambda f: f.damage),
    "fibre_stress_max": _fibre(lambda f: f.maximum),
    "fibre_stress_min": _fibre(lambda f: f.minimum),
    "fibre_stress_rms": _fibre(lambda f: f.rms),
    "spectral_loads": _spectral_loads,
    "mean_power": _mean_power,
    "rms_stroke": _rms_stroke,
    "force_limit_time": _limit(0, True),
    "force_limit_episodes": _limit(1, False),
    "stroke_limit_time": _limit(2, True),
    "stroke_limit_episodes": _limit(3, False),
    "bound": _bound,
    "power_bound": _power_bound,
    "power_bound_spectral": _power_bound_spectral,
    "terms": _terms,
    **{
        f"{name}_{part}": _term(rows, part == "moment")
        for name, rows in _TERM_QUANTITIES.items()
        for part in ("force", "moment")
    },
}
"""Every quantity by name: a function of the :class:`Quantities` of a record."""


def _load_quantity(pick: LoadPick) -> Callable[[Quantities], np.ndarray | None]:
    return lambda qs: pick(qs, qs.get("loads"))


QUANTITIES.update({name: _load_quantity(pick) for name, pick in LOAD_PICKS.items()})
