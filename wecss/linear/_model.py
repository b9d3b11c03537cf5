"""The MFM equations linearised about the static equilibrium: one model that gives the state-space system with the
radiation memory realised as extra states (DESIGN.md "linearise") and the exact frequency response from the
database's A(omega) and B(omega).

States x = [xi, xi_dot, r]: generalised displacements from the equilibrium (tangent coordinates), their rates and
the radiation states of the scene's state-space fit (real modal form). Inputs u = [F_exc, f_pto]: the excitation
force on every hydro DOF (world axes) and a PTO force per PTO added to the linear controller's. Then

    M xi_ddot = -K xi - C xi_dot + Bw' (F_exc - C_r r) + G' f_pto,     r_dot = A_r r + B_r Bw xi_dot

with M = M*(q0) (A_inf with the simulator's consistency correction), K the static stiffness with its geometric
part, the moorings' springs, the generalised modes' structural stiffness and the controller's linear stiffness,
C = G' diag(c) G + diag(c_j) + Bw' C_m Bw + C_modes the controller's linear damping, the joints' own losses
(``Joint.damping``), the moorings' dampers C_m and the modes' structural damping, Bw the world-frame Jacobian of
the hydro DOFs (a generalised mode's row: the rate of its coordinate) and G the PTO transmissions
at q0. The gyroscopic and Bdot terms are quadratic in the
velocities and vanish at equilibrium.

In the frequency domain, with xi = Re[xi_hat e^{i omega t}] and the database's own A_inf:

    [-omega^2 (M_db + Bw' (A(omega) - A_inf) Bw) + i omega (C + Bw' B(omega) Bw) + K] xi_hat = Bw' F_hat(omega)

M_db = B(q0)' (M + A_inf) B(q0); A(omega) and B(omega) are interpolated linearly between the database's
frequencies, as the excitation is. This exact solution needs no radiation fit.

Modal coordinates held quasi-static (``flexible.quasi_static_above``; ``Multibody.quasi_static_velocities``) have no
rate and no acceleration in any equation, as in the generalised-alpha runner, which solves the full equations with
their rates and accelerations zero. With the kept coordinates r and the held ones h, the equations above become

    M[:, r] xi_ddot_r + C[:, r] xi_dot_r + K xi = f,     f = Bw' (F_exc - C_r r) + G' f_pto,

(the held columns of M and C, and of Bw in the radiation states' drive, act on zero rates and accelerations; the
kept coordinates' accelerations still load the held rows through M_hr). The held rows are algebraic and give

    xi_h = K_hh^-1 (f_h - M_hr xi_ddot_r - C_hr xi_dot_r - K_hr xi_r),

and the kept rows, with T = K_rh K_hh^-1 and P = [I, -T] (kept columns first), the condensed equations

    P M[:, r] xi_ddot_r + P C[:, r] xi_dot_r + P K[:, r] xi_r = P f

(static condensation, with the inertia of the kept coordinates' motion on the held rows; the condensed mass is not
symmetric). The state space then has the states [xi_r, xi_dot_r, r]; its outputs keep every coordinate (a held one's
value from the states and the inputs, through the feedthrough D; its rate zero, as the runner records it). The
matrices ``mass``, ``damping`` and ``stiffness`` stay those of all the coordinates (the runner's iteration uses them),
and the exact frequency response solves the full equations with the held columns of the inertia and damping terms
left out, which is the same condensation.
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from functools import partial
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr
from scipy.linalg import expm

from ..compiled import CompiledScene, RadiationKind, interpolate_matrices, linear_damping
from ..compiled.kernels import kinematics, pto_strokes, world_jacobian
from ..multibody import body_mass_matrix
from ..radiation import RadiationStateSpace
from ._drag import LinearisedDrag, linearise_drag
from ._modal_recursion import ModalForm, ModalSteps

if (
    TYPE_CHECKING
):  # python-control pulls in matplotlib.pyplot and scipy.signal (~0.7 s): imported where a system is built
    import control


def equilibrium_maps(compiled: CompiledScene) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """At the static equilibrium: B (n_cart, nv), the world-frame Jacobian of the hydro DOFs Bw (n_h, nv), the PTO
    transmissions G (n_pto, nv) and the PTO strokes from their rest positions (n_pto,)."""
    p = compiled.plant
    rot, pos, b, _, _ = kinematics(p, compiled.q0, np.zeros(p.twists.shape[0]))
    stroke, g = pto_strokes(p, compiled.q0, rot, pos, b)
    return b, world_jacobian(p, rot, b)[p.hydro_index], g, stroke - p.pto_rest


def cartesian_mass(compiled: CompiledScene, q: np.ndarray) -> np.ndarray:
    """The plant's Cartesian mass (n_cart, n_cart) at the configuration ``q``: the bodies' mass with the
    simulator's A_inf (``Plant.total_mass``), a flexible body's rotation and mode rows its M(xi) at the modal
    coordinates of ``q`` (the plant holds the undeformed one) [kg, kg m, kg m^2]."""
    p = compiled.plant
    model = compiled.device.model
    if not model.elastic_bodies:
        return p.total_mass
    return p.total_mass + body_mass_matrix(model, q) - body_mass_matrix(model)


@dataclass(frozen=True)
class HydroResponse:
    """The database's frequency-dependent radiation coefficients on the hydro DOFs, for the exact frequency
    response: ``omega`` [rad/s] (n_w,), ``added_mass`` A(omega) - A_inf and ``damping`` B(omega) (n_w, n_h, n_h)
    [SI]."""

    omega: np.ndarray
    added_mass: np.ndarray
    damping: np.ndarray

    def at(self, omega: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """A(omega) - A_inf and B(omega) interpolated linearly at ``omega`` [rad/s] (n, n_h, n_h)."""
        return (
            interpolate_matrices(self.omega, self.added_mass, omega),
            interpolate_matrices(self.omega, self.damping, omega),
        )


class NoStateSpace(ValueError):
    """The model has no state-space system (its scene's radiation memory is not a state-space fit)."""


@dataclass(frozen=True, eq=False)
class LinearModel:
    """A device linearised about its static equilibrium (see the module docstring).

    Attributes
    ----------
    mass, damping, stiffness : ndarray (nv, nv)
        M* (with the A_inf of the scene's radiation memory), the linear damping C (the controller's PTO damping,
        the joints' own losses and the moorings' dampers) and the static stiffness K with its geometric part, the
        moorings' springs and the controller's stiffness [SI per generalised coordinate].
    database_mass : ndarray (nv, nv)
        M* with the database's own A_inf, which the exact frequency response completes with A(omega) - A_inf.
    hydro_jacobian : ndarray (n_h, nv)
        Bw at the equilibrium; ``pto_jacobian`` (n_pto, nv): G.
    hydro : HydroResponse
        A(omega) - A_inf and B(omega) of the database.
    q0 : ndarray
        The equilibrium configuration.
    pto_stroke : ndarray (n_pto,)
        PTO strokes at the equilibrium, from their rest positions [m or rad].
    pto_damping, pto_stiffness : ndarray (n_pto,)
        The linear PTO gains folded into ``damping`` (G' diag(c) G) and ``stiffness`` (G' diag(k) G with the rest)
        [N s/m or N m s/rad; N/m or N m/rad]: the scene's controller's when it has linear gains, else zero (an
        open plant, driven through the PTO force inputs). :meth:`with_pto_gains` folds in others.
    radiation : RadiationStateSpace or None
        The radiation states' model (real modal form); None when the scene's memory is a convolution.
    system : control.StateSpace or None
        Continuous-time model with named states, inputs and outputs, built on first use of :attr:`state_space`
        (python-control takes about a second to import, and the frequency-domain uses of the model, such as the
        power bound of every run, do not need it): None without ``radiation`` or before that first use.
    build_system : callable or None
        Makes ``system`` (used by :attr:`state_space`).
    drag : LinearisedDrag or None
        The scene's body drag linearised in its sea state (``hydrodynamics.drag``): its equivalent damping is in
        ``damping``; its forcing by the fluid's velocity, per wave component, is ``drag.forcing`` (the runs add
        it to the excitation's generalised force). None without drag.
    held : ndarray (nv,) of bool or None
        Per generalised velocity: a modal coordinate held quasi-static (``Multibody.quasi_static_velocities``),
        statically condensed out of the state space (module docstring); None when none is held.
    """

    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    database_mass: np.ndarray
    hydro_jacobian: np.ndarray
    pto_jacobian: np.ndarray
    hydro: HydroResponse
    q0: np.ndarray
    pto_stroke: np.ndarray
    pto_damping: np.ndarray
    pto_stiffness: np.ndarray
    radiation: RadiationStateSpace | None
    system: control.StateSpace | None
    build_system: Callable[[], control.StateSpace] | None = field(default=None, repr=False)
    drag: LinearisedDrag | None = None
    held: np.ndarray | None = None

    @property
    def state_space(self) -> control.StateSpace:
        """The state-space system (built on first use).

        Raises
        ------
        NoStateSpace
            When the model has none (compile the scene with ``radiation.method = "state_space"``).
        """
        if self.system is None and self.build_system is not None:
            object.__setattr__(self, "system", self.build_system())
        if self.system is None:
            raise NoStateSpace(
                "this linear model has no state-space system: compile the scene with radiation.method = "
                "'state_space' (or 'none') so that the radiation memory is a set of states"
            )
        return self.system

    def dynamic_stiffness(self, omega: np.ndarray) -> np.ndarray:
        """Z(omega) (n_omega, nv, nv) with Z xi_hat = generalised force amplitudes: the bracket of the module
        docstring's frequency-domain equation, exact from the database's A(omega) and B(omega), with the folded PTO
        gains [SI per generalised coordinate]. A held coordinate's columns keep their stiffness only (no rate, no
        acceleration: the module docstring's condensation, solved with every coordinate)."""
        omega = np.atleast_1d(np.asarray(omega, dtype=float))
        added, damping = self.hydro.at(omega)
        bw = self.hydro_jacobian
        if self.held is not None:  # no rate and no acceleration of a held coordinate: its columns of M and C out
            kept = (~self.held).astype(float)
            moving = bw * kept
            return (
                -(omega**2)[:, None, None] * (self.database_mass[None] * kept + bw.T @ added @ moving)
                + 1j * omega[:, None, None] * (self.damping[None] * kept + bw.T @ damping @ moving)
                + self.stiffness[None]
            )
        return (
            -(omega**2)[:, None, None] * (self.database_mass[None] + bw.T @ added @ bw)
            + 1j * omega[:, None, None] * (self.damping[None] + bw.T @ damping @ bw)
            + self.stiffness[None]
        )

    def frequency_response(self, omega: np.ndarray) -> np.ndarray:
        """Exact transfer matrix H(omega) = Z(omega)^-1 Bw' (n_omega, nv, n_h) from hydro-DOF force amplitudes to
        generalised displacement amplitudes (see :meth:`dynamic_stiffness`) [SI]."""
        z = self.dynamic_stiffness(omega)
        bw = self.hydro_jacobian
        return np.linalg.solve(z, np.broadcast_to(bw.T, (z.shape[0], *bw.T.shape)).astype(complex))

    def with_pto_gains(self, damping: np.ndarray | float = 0.0, stiffness: np.ndarray | float = 0.0) -> LinearModel:
        """The same device with the linear PTO gains ``damping`` and ``stiffness`` (one per PTO or one for all)
        folded in instead of the present ones: f = -c x_dot - k x on every PTO stroke x [SI]. The gains act about
        this model's equilibrium (a stiffness's static offset on a preloaded stroke is not included). With no
        arguments: the open plant.

        Raises
        ------
        ValueError
            If a gain is not finite or has the wrong number of values.
        """
        n_pto = self.pto_jacobian.shape[0]
        gains = []
        for label, value in (("damping", damping), ("stiffness", stiffness)):
            array = np.broadcast_to(np.asarray(value, dtype=float), (n_pto,)) if np.size(value) in (1, n_pto) else None
            if array is None or not np.all(np.isfinite(array)):
                raise ValueError(f"{label}: expected 1 or {n_pto} finite values; got {value!r}")
            gains.append(array.copy())
        g = self.pto_jacobian
        change_c = g.T @ np.diag(gains[0] - self.pto_damping) @ g
        change_k = g.T @ np.diag(gains[1] - self.pto_stiffness) @ g
        build = None
        if self.held is not None and (self.system is not None or self.build_system is not None):
            # the condensation depends on the stiffness and damping of every row: the system made again
            held, rad = self.held, self.radiation
            damping_, stiffness_ = self.damping + change_c, self.stiffness + change_k

            def build() -> control.StateSpace:
                base = self.state_space
                assert rad is not None
                labels = _Labels.of(base, self.mass.shape[0])
                return _state_space(labels, rad, self.mass, damping_, stiffness_, self.hydro_jacobian, g, held)

        elif self.system is not None or self.build_system is not None:

            def build() -> control.StateSpace:
                base = self.state_space
                nv = self.mass.shape[0]
                a = np.array(base.A, dtype=float)
                minv = np.linalg.inv(self.mass)
                a[nv : 2 * nv, :nv] -= minv @ change_k
                a[nv : 2 * nv, nv : 2 * nv] -= minv @ change_c
                import control

                return control.ss(
                    a, base.B, base.C, base.D, states=list(base.state_labels), inputs=list(base.input_labels),
                    outputs=list(base.output_labels), name=base.name,
                )  # fmt: skip

        return replace(
            self,
            damping=self.damping + change_c,
            stiffness=self.stiffness + change_k,
            pto_damping=gains[0],
            pto_stiffness=gains[1],
            system=None,
            build_system=build,
        )

    def with_radiation(self, radiation: RadiationStateSpace) -> LinearModel:
        """The same device with other radiation states ``radiation`` (a reduced model of this one's memory, say;
        same DOFs): the state-space system's radiation block replaced, the rest (masses, damping, stiffness, the
        exact frequency response from the database) unchanged.

        Raises
        ------
        NoStateSpace
            When this model has no state-space system.
        ValueError
            If ``radiation`` has other DOFs than this model's radiation states.
        """
        system = self.state_space
        if self.radiation is None or tuple(radiation.dofs) != tuple(self.radiation.dofs):
            raise ValueError(
                f"radiation DOFs {tuple(radiation.dofs)} differ from this model's "
                f"{None if self.radiation is None else tuple(self.radiation.dofs)}"
            )
        nv, nz = self.mass.shape[0], radiation.n_states
        bw = self.hydro_jacobian
        if self.held is not None:  # the condensed system made with the other radiation states
            made = _state_space(_Labels.of(system, nv), radiation, self.mass, self.damping, self.stiffness, bw,
                                self.pto_jacobian, self.held)  # fmt: skip
            return replace(self, radiation=radiation, system=made, build_system=None)
        a = np.zeros((2 * nv + nz, 2 * nv + nz))
        a[: 2 * nv, : 2 * nv] = np.asarray(system.A)[: 2 * nv, : 2 * nv]
        a[nv : 2 * nv, 2 * nv :] = -np.linalg.solve(self.mass, bw.T @ radiation.C)
        a[2 * nv :, nv : 2 * nv] = radiation.B @ bw
        a[2 * nv :, 2 * nv :] = radiation.A
        bmat = np.zeros((2 * nv + nz, system.ninputs))
        bmat[: 2 * nv] = np.asarray(system.B)[: 2 * nv]
        c = np.zeros((system.noutputs, 2 * nv + nz))
        c[:, : 2 * nv] = np.asarray(system.C)[:, : 2 * nv]
        labels = list(system.state_labels)[: 2 * nv]
        import control  # lazy: python-control pulls in matplotlib and scipy.signal

        reduced = control.ss(
            a, bmat, c, system.D, states=[*labels, *(f"radiation_{k}" for k in range(nz))],
            inputs=list(system.input_labels), outputs=list(system.output_labels), name=system.name,
        )  # fmt: skip
        return replace(self, radiation=radiation, system=reduced)

    @property
    def n_states(self) -> int:
        """Number of states (2 nv + radiation states; 2 n_kept + radiation states with held coordinates)."""
        return int(self.state_space.nstates)

    @property
    def n_kept(self) -> int:
        """Number of generalised coordinates among the states (nv less the held ones)."""
        nv = self.mass.shape[0]
        return nv if self.held is None else int(nv - np.count_nonzero(self.held))

    @property
    def force_input(self) -> np.ndarray:
        """Input matrix (n_states, nv) of generalised forces: every input acts through it (the excitation as
        Bw' F_exc, the PTO forces as G' f_pto). With held coordinates: (P M[:, r])^-1 P on the kept rates' rows
        (module docstring)."""
        nv = self.mass.shape[0]
        out = np.zeros((self.n_states, nv))
        if self.held is not None:
            condensed = _condense(self.mass, self.damping, self.stiffness, self.held)
            n_r = condensed.kept.size
            out[n_r : 2 * n_r] = np.linalg.solve(condensed.mass, condensed.projection)
            return out
        out[nv : 2 * nv] = np.linalg.inv(self.mass)
        return out

    def refuse_held(self, caller: str) -> None:
        """For the uses that take the generalised coordinates as the first states (``caller`` names the use).

        Raises
        ------
        ValueError
            If coordinates are held quasi-static (their values are outputs with a feedthrough of the forces,
            :meth:`coordinate_maps`, not states).
        """
        if self.held is not None:
            raise ValueError(
                f"{caller}: the linear model condenses {int(np.count_nonzero(self.held))} modal coordinates held "
                f"quasi-static (flexible.quasi_static_above; velocities {np.flatnonzero(self.held).tolist()}) out "
                "of its states, and this use needs every coordinate among them; leave quasi_static_above out, or "
                "run the scene with solver.method 'generalized-alpha', 'linear' or 'frequency'"
            )

    def output_maps(self) -> tuple[np.ndarray, np.ndarray]:
        """Rows (3 nv, n_states) and feedthrough (3 nv, nv) with [xi; xi_dot; xi_ddot] = rows x + feed f, for the
        state x and the generalised forces f (``force_input``'s) [SI]: the displacements of :meth:`coordinate_maps`,
        the rates (a held coordinate's zero) and the accelerations (a held coordinate's zero)."""
        nv, n = self.mass.shape[0], self.n_states
        a = np.asarray(self.state_space.A)
        rows, feed = np.zeros((3 * nv, n)), np.zeros((3 * nv, nv))
        if self.held is None:
            rows[: 2 * nv, : 2 * nv] = np.eye(2 * nv)
            rows[2 * nv :] = a[nv : 2 * nv]
            feed[2 * nv :] = self.force_input[nv : 2 * nv]
            return rows, feed
        kept = np.flatnonzero(~self.held)
        n_r = kept.size
        rows[:nv], feed[:nv] = self.coordinate_maps()
        rows[nv + kept, n_r : 2 * n_r] = np.eye(n_r)
        rows[2 * nv + kept] = a[n_r : 2 * n_r]
        feed[2 * nv + kept] = self.force_input[n_r : 2 * n_r]
        return rows, feed

    def coordinate_maps(self) -> tuple[np.ndarray, np.ndarray]:
        """X (nv, n_states) and Y (nv, nv) with the generalised displacements from the equilibrium xi = X x + Y f,
        for the state x and the generalised forces f (``force_input``'s: Bw' F_exc + G' f_pto) [SI]: xi is the
        first nv states (Y = 0) unless coordinates are held, whose values the held rows give (module
        docstring)."""
        nv = self.mass.shape[0]
        n = self.n_states
        if self.held is None:
            return np.eye(nv, n), np.zeros((nv, nv))
        assert self.radiation is not None
        return _coordinate_maps(
            _condense(self.mass, self.damping, self.stiffness, self.held), np.asarray(self.state_space.A),
            self.mass, self.damping, self.stiffness, self.hydro_jacobian, self.radiation,
        )  # fmt: skip

    @property
    def modal_form(self) -> ModalForm:
        """The state matrix in modal coordinates (computed once; see ``wecss.linear.ModalForm``)."""
        cached = self.__dict__.get("_modal_form")
        if cached is None:
            cached = ModalForm.of(np.asarray(self.state_space.A))
            object.__setattr__(self, "_modal_form", cached)
        return cached

    def modal_steps(self, dt: float, hold: str = "foh") -> ModalSteps:
        """The exact step of ``dt`` [s] in modal coordinates for generalised-force inputs (cached per dt and
        hold)."""
        if not (np.isfinite(dt) and dt > 0):
            raise ValueError(f"dt must be a positive finite step [s]; got {dt!r}")
        cache = self.__dict__.setdefault("_modal_steps", {})
        if (float(dt), hold) not in cache:
            cache[float(dt), hold] = self.modal_form.steps(self.force_input, dt, hold)
        return cache[float(dt), hold]

    def to_dataset(self) -> xr.Dataset:
        """The matrices with their labels, for netCDF export (``wecss.results.save``); :meth:`from_dataset`
        reads them back (models with a state-space system only)."""
        sys = self.state_space
        rad = self.radiation
        assert rad is not None
        nv = self.mass.shape[0]
        held = {} if self.held is None else {"quasi_static": (("dof",), self.held, {"long_name": "held quasi-static"})}
        return xr.Dataset(
            {
                **held,
                "A": (("state", "state_col"), np.asarray(sys.A), {"long_name": "state matrix"}),
                "B": (("state", "input"), np.asarray(sys.B), {"long_name": "input matrix"}),
                "C": (("output", "state"), np.asarray(sys.C), {"long_name": "output matrix"}),
                "D": (("output", "input"), np.asarray(sys.D), {"long_name": "feedthrough matrix"}),
                "mass": (("dof", "dof_col"), self.mass, {"long_name": "M* with A_inf at equilibrium"}),
                "database_mass": (
                    ("dof", "dof_col"),
                    self.database_mass,
                    {"long_name": "M* with the database's A_inf"},
                ),
                "damping": (("dof", "dof_col"), self.damping, {"long_name": "linear damping G' diag(c) G + diag(c_j)"}),
                "stiffness": (
                    ("dof", "dof_col"),
                    self.stiffness,
                    {"long_name": "static stiffness with geometric part"},
                ),
                "hydro_jacobian": (("hydro_dof", "dof"), self.hydro_jacobian),
                "pto_jacobian": (("pto", "dof"), self.pto_jacobian),
                "q0": (("coordinate",), self.q0, {"long_name": "static equilibrium configuration"}),
                "pto_stroke": (("pto",), self.pto_stroke, {"long_name": "PTO stroke at equilibrium"}),
                "pto_damping": (("pto",), self.pto_damping, {"long_name": "PTO damping folded in"}),
                "pto_stiffness": (("pto",), self.pto_stiffness, {"long_name": "PTO stiffness folded in"}),
                "radiation_A": (("radiation_state", "radiation_state_col"), rad.A),
                "radiation_B": (("radiation_state", "hydro_dof"), rad.B),
                "radiation_C": (("hydro_dof", "radiation_state"), rad.C),
                "hydro_added_mass": (("omega", "hydro_dof", "hydro_dof_col"), self.hydro.added_mass),
                "hydro_damping": (("omega", "hydro_dof", "hydro_dof_col"), self.hydro.damping),
            },
            coords={
                "state": list(sys.state_labels),
                "input": list(sys.input_labels),
                "output": list(sys.output_labels),
                "dof": list(sys.output_labels[:nv]),
                "hydro_dof": list(rad.dofs),
                "omega": self.hydro.omega,
                "pto": [label.removeprefix("force__") for label in sys.input_labels[len(rad.dofs) :]],
            },
            attrs={
                "title": sys.name,
                "radiation_method": rad.method,
            },
        )

    @classmethod
    def from_dataset(cls, ds: xr.Dataset) -> LinearModel:
        """Inverse of :meth:`to_dataset`."""
        import control

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
        n_r, n_h = ds.sizes.get("radiation_state", 0), ds.sizes.get("hydro_dof", 0)  # either may be absent (none)
        rad = RadiationStateSpace(
            ds.radiation_A.values.reshape(n_r, n_r),
            ds.radiation_B.values.reshape(n_r, n_h),
            ds.radiation_C.values.reshape(n_h, n_r),
            tuple(str(d) for d in ds.hydro_dof.values) if "hydro_dof" in ds.coords else (),
            str(ds.attrs.get("radiation_method", "given")),
        )
        hydro = HydroResponse(ds.omega.values, ds.hydro_added_mass.values, ds.hydro_damping.values)
        return cls(
            ds.mass.values, ds.damping.values, ds.stiffness.values, ds.database_mass.values, ds.hydro_jacobian.values,
            ds.pto_jacobian.values.reshape(ds.sizes["pto"], -1), hydro, ds.q0.values, ds.pto_stroke.values,
            ds.pto_damping.values, ds.pto_stiffness.values, rad, sys, None, None,
            ds.quasi_static.values.astype(bool) if "quasi_static" in ds else None,
        )  # fmt: skip

    def discretise(self, dt: float, hold: str = "foh") -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Exact discretisation x_{k+1} = Phi x_k + G0 u_k + G1 u_{k+1} over the step ``dt`` [s].

        ``hold``: "foh" (inputs linear in time over a step: second order for smooth forcing; exact for such inputs)
        or "zoh" (inputs held: G1 = 0, first order). Computed once per step and hold (matrix exponential of
        the augmented system); :meth:`modal_steps` is the same step in modal coordinates, which the runs use.
        """
        if hold not in ("foh", "zoh"):
            raise ValueError(f"hold must be 'foh' or 'zoh'; got {hold!r}")
        if not (np.isfinite(dt) and dt > 0):
            raise ValueError(f"dt must be a positive finite step [s]; got {dt!r}")
        cache = self.__dict__.setdefault("_discretised", {})
        if (float(dt), hold) not in cache:
            cache[float(dt), hold] = self._discretise(dt, hold)
        return cache[float(dt), hold]

    def _discretise(self, dt: float, hold: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        phi, now, after = exact_step(np.asarray(self.state_space.A), np.asarray(self.state_space.B), dt)
        if hold == "zoh":
            return phi, now + after, np.zeros_like(now)
        return phi, now, after


def exact_step(a: np.ndarray, b: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Exact step of x' = a x + b u over ``dt`` [s] with u linear in time between its samples (first-order
    hold): x_{k+1} = Phi x_k + G0 u_k + G1 u_{k+1}; with u held, the input matrix is G0 + G1. From the matrix
    exponential of the augmented system.

    Raises
    ------
    ValueError
        If ``dt`` is not a positive finite step (an infinite one gives NaN matrices).
    """
    if not (np.isfinite(dt) and dt > 0):
        raise ValueError(f"dt must be a positive finite step [s]; got {dt!r}")
    n, m = b.shape
    block = np.zeros((n + 2 * m, n + 2 * m))
    block[:n, :n] = a * dt
    block[:n, n : n + m] = b * dt
    block[n : n + m, n + m :] = np.eye(m)
    e = expm(block)
    phi, theta1, theta2 = e[:n, :n], e[:n, n : n + m], e[:n, n + m :]
    return phi, theta1 - theta2, theta2


def _radiation_model(compiled: CompiledScene) -> RadiationStateSpace | None:
    """The radiation states the scene's simulation uses (its compiled fit), none for no memory, or None for a
    convolution."""
    if compiled.radiation_fit is not None:
        return compiled.radiation_fit.model.real_modal()
    if compiled.radiation_summary.kind == RadiationKind.NONE:
        n_h = len(compiled.hydro.dofs)
        empty = (np.zeros((0, 0)), np.zeros((0, n_h)), np.zeros((n_h, 0)))
        return RadiationStateSpace(*empty, tuple(compiled.hydro.dofs), "none")
    return None


CACHE_SIZE: int = 32
"""Linear models kept in memory by :func:`linearize`, by scene fingerprint (least recently used dropped)."""

_CACHE: OrderedDict[str, LinearModel] = OrderedDict()


def linearize(
    compiled: CompiledScene, radiation: RadiationStateSpace | None = None, *, cache: bool = True
) -> LinearModel:
    """The linearised MFM model of a compiled scene about its static equilibrium.

    Models of the scene's own radiation memory are cached in memory by the scene's fingerprint
    (:attr:`CompiledScene.fingerprint`: scene without outputs, device, data, waves) and the compiled mass,
    stiffness and PTO gains (which a changed copy of a compiled scene may not share), with their modal form and
    discretisations, so a second call on the same scene (recompiled or not) costs nothing. The fit itself is
    cached on disk by ``wecss.radiation``. The cached model is shared: do not modify its arrays.

    Parameters
    ----------
    compiled : CompiledScene
        Its controller's linear gains are folded into the model (other controllers act through the PTO inputs).
        The state-space system needs ``radiation.method = "state_space"`` (its A_inf correction belongs to the fit
        used here) or ``"none"``; with a convolution the model has the matrices and the exact frequency response
        only.
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
        If ``radiation`` is given for a scene whose memory is not a state-space model (its A_inf correction
        would not belong to those states), or its DOFs differ from the database's.
    TypeError
        If ``compiled`` is not a CompiledScene.
    """
    if not isinstance(compiled, CompiledScene):
        raise TypeError(
            f"linearize takes a CompiledScene (wecss.sim.compile_scene(scene)); got {type(compiled).__name__}"
        )
    kind = compiled.radiation_summary.kind
    if radiation is not None and kind == RadiationKind.CONVOLUTION:
        raise ValueError(
            "compile the scene with radiation.method = 'state_space' to linearise it with radiation states (its "
            f"A_inf correction must belong to the radiation states used); it has {kind.method!r}"
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
    b, bw, g, stroke = equilibrium_maps(compiled)
    mass = b.T @ cartesian_mass(compiled, compiled.q0) @ b
    mass = 0.5 * (mass + mass.T)
    # the database's own A_inf: the exact frequency response adds A(omega) - A_inf (no memory-model correction)
    body_mass = body_mass_matrix(compiled.device.model, compiled.q0)
    database = b.T @ (body_mass + compiled.coupling.added_mass_inf) @ b
    stiffness = compiled.stiffness  # device springs and the controller's stiffness included
    # the joints' own losses and the moorings' dampers too
    damping = linear_damping(p, g, bw)
    ds = compiled.hydro.dataset
    hydro = HydroResponse(
        compiled.hydro.omega, ds.added_mass.values - ds.added_mass_inf.values[None], ds.radiation_damping.values
    )
    rad = radiation.real_modal() if radiation is not None else _radiation_model(compiled)
    quasi_static = np.asarray(compiled.device.model.quasi_static_velocities, dtype=bool)
    held = quasi_static.copy() if quasi_static.any() else None
    if held is not None:
        _condense(mass, damping, stiffness, held)  # refused here if the held coordinates have no stiffness
    drag = None
    if compiled.scene.hydrodynamics.drag:  # the body drag linearised in the sea state (wecss.linear._drag)
        bare = LinearModel(
            mass, damping, stiffness, 0.5 * (database + database.T), bw, g, hydro, compiled.q0, stroke,
            p.pto_damping.copy(), p.pto_stiffness.copy(), rad, None, None, None, held,
        )  # fmt: skip
        drag = linearise_drag(compiled, bare.dynamic_stiffness, bw)
        if drag is not None:
            damping = damping + drag.damping
    build = None
    if rad is not None:
        if tuple(rad.dofs) != tuple(compiled.hydro.dofs):
            raise ValueError(f"radiation model DOFs {rad.dofs} differ from the database's {compiled.hydro.dofs}")
        labels = _Labels(
            tuple(compiled.device.model.velocity_names),
            tuple(pto.name for pto in compiled.device.ptos),
            tuple(compiled.hydro.dofs),
            compiled.device.name,
        )  # only the names: the cached model must not keep the compiled scene alive
        build = partial(_state_space, labels, rad, mass, damping, stiffness, bw, g, held)
    return LinearModel(
        mass, damping, stiffness, 0.5 * (database + database.T), bw, g, hydro, compiled.q0, stroke,
        p.pto_damping.copy(), p.pto_stiffness.copy(), rad, None, build, drag, held,
    )  # fmt: skip


@dataclass(frozen=True)
class _Labels:
    """Names of the state-space system's states, inputs and outputs."""

    velocities: tuple[str, ...]
    ptos: tuple[str, ...]
    hydro_dofs: tuple[str, ...]
    device: str

    @classmethod
    def of(cls, system: control.StateSpace, nv: int) -> _Labels:
        """The names of a system made by :func:`_state_space` (``nv`` generalised velocities)."""
        inputs = list(system.input_labels)
        return cls(
            tuple(system.output_labels[:nv]),
            tuple(label.removeprefix("force__") for label in inputs if label.startswith("force__")),
            tuple(label.removeprefix("excitation__") for label in inputs if label.startswith("excitation__")),
            str(system.name).removesuffix(" linearised"),
        )


@dataclass(frozen=True)
class _Condensed:
    """The static condensation of the held coordinates (module docstring): the kept and held velocities' indices,
    P = [I, -K_rh K_hh^-1] (n_r, nv) on the velocities' order, and the condensed P M[:, r], P C[:, r], P K[:, r]
    (n_r, n_r)."""

    kept: np.ndarray
    held: np.ndarray
    projection: np.ndarray
    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray


def _condense(mass: np.ndarray, damping: np.ndarray, stiffness: np.ndarray, held: np.ndarray) -> _Condensed:
    """The condensation of the coordinates ``held`` (nv,) bool out of M, C, K (nv, nv).

    Raises
    ------
    ValueError
        If the held coordinates' stiffness K_hh is singular (their equations cannot be solved for them).
    """
    kept, out = np.flatnonzero(~held), np.flatnonzero(held)
    k_hh = stiffness[np.ix_(out, out)]
    if np.linalg.matrix_rank(k_hh) < out.size:
        raise ValueError(
            f"the stiffness of the {out.size} coordinates held quasi-static (flexible.quasi_static_above) is "
            "singular: their algebraic equations do not fix them (hold only modal coordinates with a stiffness)"
        )
    transfer = np.linalg.solve(k_hh.T, stiffness[np.ix_(kept, out)].T).T  # K_rh K_hh^-1
    projection = np.zeros((kept.size, held.size))
    projection[:, kept] = np.eye(kept.size)
    projection[:, out] = -transfer
    return _Condensed(
        kept, out, projection, projection @ mass[:, kept], projection @ damping[:, kept],
        projection @ stiffness[:, kept],
    )  # fmt: skip


def _coordinate_maps(
    condensed: _Condensed,
    a: np.ndarray,
    mass: np.ndarray,
    damping: np.ndarray,
    stiffness: np.ndarray,
    bw: np.ndarray,
    rad: RadiationStateSpace,
) -> tuple[np.ndarray, np.ndarray]:
    """X (nv, n) and Y (nv, nv) with xi = X x + Y f for the condensed system's state matrix ``a`` (n, n): the kept
    coordinates are the first states, the held ones xi_h = K_hh^-1 (f_h - Bw_h' C_r r - M_hr xi_ddot_r -
    C_hr xi_dot_r - K_hr xi_r) with xi_ddot_r = a[n_r:2 n_r] x + (P M[:, r])^-1 P f."""
    kept, out = condensed.kept, condensed.held
    n_r, nv, n = kept.size, mass.shape[0], a.shape[0]
    acceleration_state = a[n_r : 2 * n_r]
    acceleration_force = np.linalg.solve(condensed.mass, condensed.projection)
    k_hh = stiffness[np.ix_(out, out)]
    m_hr = mass[np.ix_(out, kept)]
    rows = np.zeros((out.size, n))  # the held rows' loads from the state, less the inertia of the kept motion
    rows[:, :n_r] = -stiffness[np.ix_(out, kept)]
    rows[:, n_r : 2 * n_r] = -damping[np.ix_(out, kept)]
    rows[:, 2 * n_r :] = -bw[:, out].T @ rad.C
    rows -= m_hr @ acceleration_state
    force = -m_hr @ acceleration_force
    force[:, out] += np.eye(out.size)
    x_map = np.zeros((nv, n))
    y_map = np.zeros((nv, nv))
    x_map[kept, :n_r] = np.eye(n_r)
    x_map[out] = np.linalg.solve(k_hh, rows)
    y_map[out] = np.linalg.solve(k_hh, force)
    return x_map, y_map


def _state_space(
    labels: _Labels,
    rad: RadiationStateSpace,
    mass: np.ndarray,
    damping: np.ndarray,
    stiffness: np.ndarray,
    bw: np.ndarray,
    g: np.ndarray,
    held: np.ndarray | None = None,
) -> control.StateSpace:
    """The state-space system of the module docstring with named states, inputs and outputs; with ``held``
    (nv,) bool, the held coordinates condensed out (:func:`_condensed_space`)."""
    if held is not None:
        return _condensed_space(labels, rad, mass, damping, stiffness, bw, g, held)
    nv = mass.shape[0]
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
    names = list(labels.velocities)
    ptos = list(labels.ptos)
    import control

    return control.ss(
        a,
        bmat,
        c,
        np.zeros((c.shape[0], bmat.shape[1])),
        states=[*names, *(f"{n}__rate" for n in names), *(f"radiation_{k}" for k in range(nz))],
        inputs=[*(f"excitation__{d}" for d in labels.hydro_dofs), *(f"force__{n}" for n in ptos)],
        outputs=[
            *names,
            *(f"{n}__rate" for n in names),
            *(f"stroke__{n}" for n in ptos),
            *(f"stroke_rate__{n}" for n in ptos),
        ],
        name=f"{labels.device} linearised",
    )


def _condensed_space(
    labels: _Labels,
    rad: RadiationStateSpace,
    mass: np.ndarray,
    damping: np.ndarray,
    stiffness: np.ndarray,
    bw: np.ndarray,
    g: np.ndarray,
    held: np.ndarray,
) -> control.StateSpace:
    """The state-space system with the ``held`` coordinates condensed out (module docstring): states [xi_r,
    xi_dot_r, r], the same inputs, and the same outputs (every coordinate, a held one's rate zero, the PTO strokes
    and rates), a held coordinate's value through the feedthrough D."""
    condensed = _condense(mass, damping, stiffness, held)
    kept = condensed.kept
    nv, n_r, nz = mass.shape[0], kept.size, rad.n_states
    n_h, n_pto = bw.shape[0], g.shape[0]
    n = 2 * n_r + nz
    to_rate = np.linalg.solve(condensed.mass, condensed.projection)  # generalised force -> kept accelerations
    a = np.zeros((n, n))
    a[:n_r, n_r : 2 * n_r] = np.eye(n_r)
    a[n_r : 2 * n_r, :n_r] = -np.linalg.solve(condensed.mass, condensed.stiffness)
    a[n_r : 2 * n_r, n_r : 2 * n_r] = -np.linalg.solve(condensed.mass, condensed.damping)
    a[n_r : 2 * n_r, 2 * n_r :] = -to_rate @ bw.T @ rad.C
    a[2 * n_r :, n_r : 2 * n_r] = rad.B @ bw[:, kept]
    a[2 * n_r :, 2 * n_r :] = rad.A
    forces = np.hstack([bw.T, g.T])  # inputs -> generalised forces (nv, n_h + n_pto)
    bmat = np.zeros((n, n_h + n_pto))
    bmat[n_r : 2 * n_r] = to_rate @ forces
    x_map, y_map = _coordinate_maps(condensed, a, mass, damping, stiffness, bw, rad)
    rate_map = np.zeros((nv, n))
    rate_map[kept, n_r : 2 * n_r] = np.eye(n_r)
    c = np.vstack([x_map, rate_map, g @ x_map, g @ rate_map])
    d = np.vstack([y_map, np.zeros((nv, nv)), g @ y_map, np.zeros((n_pto, nv))]) @ forces
    names = list(labels.velocities)
    kept_names = [names[k] for k in kept]
    ptos = list(labels.ptos)
    import control

    return control.ss(
        a,
        bmat,
        c,
        d,
        states=[*kept_names, *(f"{name}__rate" for name in kept_names), *(f"radiation_{k}" for k in range(nz))],
        inputs=[*(f"excitation__{dof}" for dof in labels.hydro_dofs), *(f"force__{pto}" for pto in ptos)],
        outputs=[
            *names,
            *(f"{name}__rate" for name in names),
            *(f"stroke__{pto}" for pto in ptos),
            *(f"stroke_rate__{pto}" for pto in ptos),
        ],
        name=f"{labels.device} linearised",
    )
