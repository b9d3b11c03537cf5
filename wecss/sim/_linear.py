"""The MFM equations linearised about the static equilibrium, as a state-space model with the radiation memory
realised as extra states (DESIGN.md "linearise"; issue 6).

States x = [xi, xi_dot, r]: generalised displacements from the equilibrium (tangent coordinates), their rates and
the radiation states of the scene's state-space fit (real modal form). Inputs u = [F_exc, f_pto]: the excitation
force on every hydro DOF (world axes) and a PTO force per PTO added to the linear controller's. Then

    M xi_ddot = -K xi - C xi_dot + Bw' (F_exc - C_r r) + G' f_pto,     r_dot = A_r r + B_r Bw xi_dot

with M = M*(q0) (A_inf with the simulator's consistency correction), K the static stiffness with its geometric
part and the controller's linear stiffness, C = G' diag(c) G the controller's linear damping, Bw the world-frame
Jacobian of the hydro DOFs and G the PTO transmissions at q0. The gyroscopic and Bdot terms are quadratic in the
velocities and vanish at equilibrium.
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict
from dataclasses import dataclass

import control
import numpy as np
import xarray as xr
from scipy.linalg import expm

from ..radiation import RadiationStateSpace
from ._compile import CompiledScene, fit_request
from ._frequency import equilibrium_maps
from ._modal_recursion import ModalForm, ModalSteps, input_forcing, outputs, real_part_rows, run


@dataclass(frozen=True, eq=False)
class LinearModel:
    """A linearised device model.

    Attributes
    ----------
    system : control.StateSpace
        Continuous-time model with named states, inputs and outputs.
    mass, damping, stiffness : ndarray (nv, nv)
        M*, C and K [SI per generalised coordinate].
    hydro_jacobian : ndarray (n_h, nv)
        Bw at the equilibrium; ``pto_jacobian`` (n_pto, nv): G.
    radiation : RadiationStateSpace
        The radiation states' model (real modal form).
    q0 : ndarray
        The equilibrium configuration.
    """

    system: control.StateSpace
    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    hydro_jacobian: np.ndarray
    pto_jacobian: np.ndarray
    radiation: RadiationStateSpace
    q0: np.ndarray

    @property
    def n_states(self) -> int:
        """Number of states (2 nv + radiation states)."""
        return int(self.system.nstates)

    @property
    def force_input(self) -> np.ndarray:
        """Input matrix (n_states, nv) of generalised forces: every input acts through it (the excitation as
        Bw' F_exc, the PTO forces as G' f_pto)."""
        nv = self.mass.shape[0]
        out = np.zeros((self.n_states, nv))
        out[nv : 2 * nv] = np.linalg.inv(self.mass)
        return out

    @property
    def modal_form(self) -> ModalForm:
        """The state matrix in modal coordinates (computed once; see ``wecss.sim._modal_recursion``)."""
        cached = self.__dict__.get("_modal_form")
        if cached is None:
            cached = ModalForm.of(np.asarray(self.system.A))
            object.__setattr__(self, "_modal_form", cached)
        return cached

    def modal_steps(self, dt: float, hold: str = "foh") -> ModalSteps:
        """The exact step of ``dt`` [s] in modal coordinates for generalised-force inputs (cached per dt and
        hold)."""
        if not dt > 0:
            raise ValueError(f"dt must be positive [s]; got {dt!r}")
        cache = self.__dict__.setdefault("_modal_steps", {})
        if (float(dt), hold) not in cache:
            cache[float(dt), hold] = self.modal_form.steps(self.force_input, dt, hold)
        return cache[float(dt), hold]

    def to_dataset(self) -> xr.Dataset:
        """The matrices with their labels, for netCDF export (``wecss.results.save``); :meth:`from_dataset`
        reads them back."""
        sys = self.system
        nv = self.mass.shape[0]
        return xr.Dataset(
            {
                "A": (("state", "state_col"), np.asarray(sys.A), {"long_name": "state matrix"}),
                "B": (("state", "input"), np.asarray(sys.B), {"long_name": "input matrix"}),
                "C": (("output", "state"), np.asarray(sys.C), {"long_name": "output matrix"}),
                "D": (("output", "input"), np.asarray(sys.D), {"long_name": "feedthrough matrix"}),
                "mass": (("dof", "dof_col"), self.mass, {"long_name": "M* with A_inf at equilibrium"}),
                "damping": (("dof", "dof_col"), self.damping, {"long_name": "linear PTO damping G' diag(c) G"}),
                "stiffness": (
                    ("dof", "dof_col"),
                    self.stiffness,
                    {"long_name": "static stiffness with geometric part"},
                ),
                "hydro_jacobian": (("hydro_dof", "dof"), self.hydro_jacobian),
                "pto_jacobian": (("pto", "dof"), self.pto_jacobian),
                "q0": (("coordinate",), self.q0, {"long_name": "static equilibrium configuration"}),
                "radiation_A": (("radiation_state", "radiation_state_col"), self.radiation.A),
                "radiation_B": (("radiation_state", "hydro_dof"), self.radiation.B),
                "radiation_C": (("hydro_dof", "radiation_state"), self.radiation.C),
            },
            coords={
                "state": list(sys.state_labels),
                "input": list(sys.input_labels),
                "output": list(sys.output_labels),
                "dof": list(sys.state_labels[:nv]),
                "hydro_dof": list(self.radiation.dofs),
                "pto": [label.removeprefix("force__") for label in sys.input_labels[len(self.radiation.dofs) :]],
            },
            attrs={"title": sys.name, "radiation_method": self.radiation.method},
        )

    @classmethod
    def from_dataset(cls, ds: xr.Dataset) -> LinearModel:
        """Inverse of :meth:`to_dataset`."""
        sys = control.ss(
            ds.A.values,
            ds.B.values,
            ds.C.values,
            ds.D.values,
            states=[str(s) for s in ds.state.values],
            inputs=[str(s) for s in ds.input.values],
            outputs=[str(s) for s in ds.output.values],
            name=str(ds.attrs.get("title", "linear model")),
        )
        rad = RadiationStateSpace(
            ds.radiation_A.values.reshape(ds.sizes.get("radiation_state", 0), -1),
            ds.radiation_B.values.reshape(ds.sizes.get("radiation_state", 0), ds.sizes["hydro_dof"]),
            ds.radiation_C.values.reshape(ds.sizes["hydro_dof"], ds.sizes.get("radiation_state", 0)),
            tuple(str(d) for d in ds.hydro_dof.values),
            str(ds.attrs.get("radiation_method", "given")),
        )
        return cls(
            sys, ds.mass.values, ds.damping.values, ds.stiffness.values, ds.hydro_jacobian.values,
            ds.pto_jacobian.values.reshape(ds.sizes["pto"], -1), rad, ds.q0.values,
        )  # fmt: skip

    def discretise(self, dt: float, hold: str = "foh") -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Exact discretisation x_{k+1} = Phi x_k + G0 u_k + G1 u_{k+1} over the step ``dt`` [s].

        ``hold``: "foh" (inputs linear in time over a step: second order for smooth forcing; exact for such inputs)
        or "zoh" (inputs held: G1 = 0, first order). Computed once per step and hold (matrix exponential of
        the augmented system); :meth:`modal_steps` is the same step in modal coordinates, which the runs use.
        """
        if hold not in ("foh", "zoh"):
            raise ValueError(f"hold must be 'foh' or 'zoh'; got {hold!r}")
        if not dt > 0:
            raise ValueError(f"dt must be positive [s]; got {dt!r}")
        cache = self.__dict__.setdefault("_discretised", {})
        if (float(dt), hold) not in cache:
            cache[float(dt), hold] = self._discretise(dt, hold)
        return cache[float(dt), hold]

    def _discretise(self, dt: float, hold: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        a, b = np.asarray(self.system.A), np.asarray(self.system.B)
        n, m = b.shape
        block = np.zeros((n + 2 * m, n + 2 * m))
        block[:n, :n] = a * dt
        block[:n, n : n + m] = b * dt
        block[n : n + m, n + m :] = np.eye(m)
        e = expm(block)
        phi, theta1, theta2 = e[:n, :n], e[:n, n : n + m], e[:n, n + m :]
        if hold == "zoh":
            return phi, theta1, np.zeros_like(theta1)
        return phi, theta1 - theta2, theta2


def _radiation_model(compiled: CompiledScene) -> RadiationStateSpace:
    from ..radiation import fit_radiation

    settings, band = fit_request(compiled.scene, compiled.hydro)
    return fit_radiation(compiled.hydro, settings, cache=True, band=band).model.real_modal()


CACHE_SIZE: int = 32
"""Linear models kept in memory by :func:`linearize`, by scene fingerprint (least recently used dropped)."""

_CACHE: OrderedDict[str, LinearModel] = OrderedDict()


def linearize(
    compiled: CompiledScene, radiation: RadiationStateSpace | None = None, *, cache: bool = True
) -> LinearModel:
    """The linearised MFM model of a compiled scene about its static equilibrium.

    Models of the scene's own radiation fit are cached in memory by the scene's fingerprint
    (:attr:`CompiledScene.fingerprint`: scene without outputs, device, data, waves) and the compiled mass,
    stiffness and PTO gains (which a changed copy of a compiled scene may not share), with their modal form and
    discretisations, so a second call on the same scene (recompiled or not) costs nothing. The fit itself is
    cached on disk by ``wecss.radiation``. The cached model is shared: do not modify its arrays.

    Parameters
    ----------
    compiled : CompiledScene
        Compiled with ``radiation.method = "state_space"`` (so that its A_inf correction belongs to the fit used
        here). Its controller's linear gains are folded into the model (other controllers act through the PTO
        inputs).
    radiation : RadiationStateSpace, optional
        Radiation states (default: the scene's state-space fit, the one its simulation uses; models with other
        radiation states are not cached).
    cache : bool
        Use and fill the in-memory cache.

    Returns
    -------
    LinearModel

    Raises
    ------
    ValueError
        If the scene was compiled with another radiation method and no ``radiation`` model is given.
    """
    if radiation is None and compiled.radiation_summary.method != "state_space":
        raise ValueError(
            "compile the scene with radiation.method = 'state_space' to linearise it (its A_inf correction must "
            f"belong to the radiation states used); it has {compiled.radiation_summary.method!r}"
        )
    key = _cache_key(compiled) if cache and radiation is None else None
    if key is not None and key in _CACHE:
        _CACHE.move_to_end(key)
        return _CACHE[key]
    model = _linearize(compiled, radiation)
    if key is not None:
        _CACHE[key] = model
        while len(_CACHE) > CACHE_SIZE:
            _CACHE.popitem(last=False)
    return model


def _cache_key(compiled: CompiledScene) -> str:
    """The scene's fingerprint and the arrays the model is built from (a compiled scene changed after compilation,
    such as another controller or PTO damping, gets another key)."""
    h = hashlib.sha256(compiled.fingerprint.encode())
    p = compiled.plant
    for array in (p.total_mass, p.pto_damping, p.pto_stiffness, compiled.stiffness, compiled.q0):
        h.update(np.ascontiguousarray(array, dtype=float).tobytes())
    h.update(bytes([compiled.linear_controller]))
    return h.hexdigest()[:32]


def _linearize(compiled: CompiledScene, radiation: RadiationStateSpace | None) -> LinearModel:
    p = compiled.plant
    q0 = compiled.q0
    nv = p.twists.shape[0]
    b, bw, g, _ = equilibrium_maps(compiled)
    mass = b.T @ p.total_mass @ b
    mass = 0.5 * (mass + mass.T)
    stiffness = compiled.stiffness
    damping = g.T @ np.diag(p.pto_damping) @ g
    rad = (radiation or _radiation_model(compiled)).real_modal()
    if tuple(rad.dofs) != tuple(compiled.hydro.dofs):
        raise ValueError(f"radiation model DOFs {rad.dofs} differ from the database's {compiled.hydro.dofs}")
    nz = rad.n_states
    n_h, n_pto = bw.shape[0], g.shape[0]
    minv = np.linalg.inv(mass)
    a = np.zeros((2 * nv + nz, 2 * nv + nz))
    a[:nv, nv : 2 * nv] = np.eye(nv)
    a[nv : 2 * nv, :nv] = -minv @ stiffness
    a[nv : 2 * nv, nv : 2 * nv] = -minv @ damping
    a[nv : 2 * nv, 2 * nv :] = -minv @ bw.T @ rad.C
    a[2 * nv :, nv : 2 * nv] = rad.B @ bw
    a[2 * nv :, 2 * nv :] = rad.A
    bmat = np.zeros((2 * nv + nz, n_h + n_pto))
    bmat[nv : 2 * nv, :n_h] = minv @ bw.T
    bmat[nv : 2 * nv, n_h:] = minv @ g.T
    c = np.zeros((2 * nv + 2 * n_pto, 2 * nv + nz))
    c[:nv, :nv] = np.eye(nv)
    c[nv : 2 * nv, nv : 2 * nv] = np.eye(nv)
    c[2 * nv : 2 * nv + n_pto, :nv] = g
    c[2 * nv + n_pto :, nv : 2 * nv] = g
    names = list(compiled.device.model.velocity_names)
    ptos = [pto.name for pto in compiled.device.ptos]
    system = control.ss(
        a,
        bmat,
        c,
        np.zeros((c.shape[0], bmat.shape[1])),
        states=[*names, *(f"{n}__rate" for n in names), *(f"radiation_{k}" for k in range(nz))],
        inputs=[*(f"excitation__{d}" for d in compiled.hydro.dofs), *(f"force__{n}" for n in ptos)],
        outputs=[
            *names,
            *(f"{n}__rate" for n in names),
            *(f"stroke__{n}" for n in ptos),
            *(f"stroke_rate__{n}" for n in ptos),
        ],
        name=f"{compiled.device.name} linearised",
    )
    return LinearModel(system, mass, damping, stiffness, bw, g, rad, q0)


def simulate_linear(compiled: CompiledScene, model: LinearModel | None = None, *, hold: str = "foh") -> xr.Dataset:
    """Time-domain run of the linear model on the scene's waves, with the exact discretisation (in modal
    coordinates: see ``wecss.sim._modal_recursion``).

    A controller with linear gains is folded into the model (open loop in the remaining inputs). Any other
    controller closes the loop: it is called once per control period (``controller.dt``, default every step)
    with the PTO strokes and rates and its force is held until the next call (zero-order hold, as in the
    nonlinear simulator); the excitation keeps the ``hold`` given.

    Returns a Dataset laid out as :func:`wecss.sim.simulate`'s (so every metric works on both).

    Raises
    ------
    ValueError
        For a device with a free base (its coordinates are not linear), or an unknown ``hold``.
    """
    import time as _time

    from ..results import build_result
    from ._jit import JIT
    from ._simulate import Record, window_statistics

    if compiled.device.model.nq != compiled.device.model.nv:
        raise ValueError("the linear simulation needs joint coordinates (no free base)")
    if hold not in ("foh", "zoh"):
        raise ValueError(f"hold must be 'foh' or 'zoh'; got {hold!r}")
    model = model or linearize(compiled)
    form, steps = model.modal_form, model.modal_steps(compiled.dt, hold)
    start = _time.perf_counter()
    p = compiled.plant
    nv, n_h, n_pto = model.mass.shape[0], model.hydro_jacobian.shape[0], model.pto_jacobian.shape[0]
    g = model.pto_jacobian
    time = compiled.time
    exc = (
        np.ascontiguousarray(compiled.excitation.force(time).T)
        if compiled.excitation is not None
        else np.zeros((time.size, n_h))
    )
    force = exc @ model.hydro_jacobian  # generalised excitation (n_t, nv)
    stroke0 = equilibrium_maps(compiled)[3]
    command = np.zeros((time.size, n_pto))
    # outputs: xi, xi_dot, the acceleration's state part and (if asked for) the radiation force
    n_states = model.n_states
    with_radiation = "radiation" in compiled.scene.outputs.variables
    rows = np.zeros((3 * nv + (n_h if with_radiation else 0), n_states))
    rows[: 2 * nv, : 2 * nv] = np.eye(2 * nv)
    rows[2 * nv : 3 * nv] = np.asarray(model.system.A)[nv : 2 * nv]
    if with_radiation:
        rows[3 * nv :, 2 * nv :] = -model.radiation.C
    if compiled.linear_controller or n_pto == 0:
        y = run(form, steps, force, rows)
    else:
        z, free = _closed_loop(compiled, model, form, steps, force, stroke0, command)
        # recorded at t_k, as by the nonlinear simulator: the force that acted over the step ending at t_k
        command = np.concatenate([np.zeros((1, n_pto)), command[:-1]])
        force += command @ g
        y = outputs(form, rows, z, free)
    every = compiled.scene.outputs.every
    keep = slice(None, None, every)
    acc = y[keep, 2 * nv : 3 * nv] + force[keep] @ model.force_input[nv : 2 * nv].T
    rad = y[keep, 3 * nv :] if with_radiation else np.zeros((acc.shape[0], n_h))
    xi, rate = y[:, :nv], y[:, nv : 2 * nv]
    stroke = stroke0[None] + xi @ g.T
    stroke_rate = rate @ g.T
    pto_force = command - (p.pto_spring + p.pto_stiffness) * stroke - p.pto_damping * stroke_rate
    stats = window_statistics(compiled, stroke, stroke_rate, pto_force)
    run_time = _time.perf_counter() - start
    record = Record(
        time[keep], (compiled.q0[None] + xi)[keep], rate[keep], acc, stroke[keep], stroke_rate[keep],
        pto_force[keep], rad, exc[keep], stats, np.zeros(3, dtype=np.int64), run_time,
    )  # fmt: skip
    ds = build_result(compiled, record, jit=JIT)
    for key in ("evaluations_per_step", "max_evaluations_per_step", "newton_corrector_steps"):
        ds.attrs.pop(key, None)
    ds.attrs["solver"] = f"linear ({hold}, exact discretisation in {form.n_modes} modal coordinates)"
    ds.attrs["radiation"] = f"state space, {model.radiation.n_states} real states (linear model)"
    return ds


def _closed_loop(
    compiled: CompiledScene,
    model: LinearModel,
    form: ModalForm,
    steps: ModalSteps,
    force: np.ndarray,
    stroke0: np.ndarray,
    command: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """The modal run with the controller called once per control period, its force held over the period (written
    into ``command``)."""
    from controllers import Measurement

    nv, n_pto = model.mass.shape[0], model.pto_jacobian.shape[0]
    g, time = model.pto_jacobian, compiled.time
    held = model.modal_steps(compiled.dt, "zoh")  # the PTO force is held over each step
    held_modes = held.input0 @ g.T  # (n_modes, n_pto)
    held_free = held.free_input0 @ g.T
    # strokes and rates from the modal coordinates and the free states
    rows = np.zeros((2 * n_pto, model.n_states))
    rows[:n_pto, :nv] = g
    rows[n_pto:, nv : 2 * nv] = g
    measure_modes, measure_free = form.output_maps(rows)
    forcing, free_forcing = input_forcing(steps, force)
    free_modes = real_part_rows(steps.free_state.T)
    z = np.zeros((time.size, form.n_modes), dtype=complex)
    free = np.zeros((time.size, form.free.size))
    control = compiled.scene.control_steps
    compiled.controller.setup(n_pto, compiled.dt * control)  # a fresh start for controllers with memory
    out = np.zeros(n_pto)
    for k in range(time.size):
        if k % control == 0:  # a control step: the controller's force is held until the next one
            measured = z[k].view(np.float64) @ measure_modes + free[k] @ measure_free
            out = np.asarray(
                compiled.controller.compute(time[k], Measurement(stroke0 + measured[:n_pto], measured[n_pto:])),
                dtype=float,
            )
            if out.shape != (n_pto,) or not np.all(np.isfinite(out)):
                raise ValueError(f"controller returned {out!r}; expected {n_pto} finite forces")
        command[k] = out
        if k + 1 < time.size:
            z[k + 1] = steps.decay * z[k] + forcing[k] + held_modes @ out
            free[k + 1] = free[k] + z[k].view(np.float64) @ free_modes + free_forcing[k] + held_free @ out
    return z, free
