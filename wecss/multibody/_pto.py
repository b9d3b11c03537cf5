"""Power take-off elements: on a joint (rotary torque on a revolute joint, linear force on a prismatic joint) or
between two points on two bodies (a linear actuator or hydraulic cylinder).

Every PTO has a scalar stroke x(q) (joint coordinate, or actuator length c(q)), its rate x_dot = g(q)' v with
the transmission g = dx/dq, and applies the generalised force Q = g(q) f for a PTO force f [N or N m]
(positive f pushes x to grow). The built-in law is the passive spring-damper f = -k (x - x_rest) - d x_dot;
controllers replace it by any f(t). Absorbed power is P = -f x_dot.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._kinematics import KinematicState
from ._se3 import hat
from ._tree import Multibody


def _check_gains(name: str, damping: float, stiffness: float) -> None:
    for label, value in (("damping", damping), ("stiffness", stiffness)):
        if not np.isfinite(value):
            raise ValueError(f"PTO {name!r}: {label} must be finite; got {value!r}")
    if damping < 0:
        raise ValueError(
            f"PTO {name!r}: damping must be >= 0 [N m s/rad or N s/m] (a negative damping supplies energy); "
            f"got {damping!r}"
        )


def _check_limits(pto: JointPTO | ActuatorPTO) -> None:
    """Limits are positive when given; an end stop needs a stroke limit and non-negative constants."""
    for label in ("force_limit", "stroke_limit"):
        value = getattr(pto, label)
        if value is not None and not (np.isfinite(value) and value > 0):
            raise ValueError(f"PTO {pto.name!r}: {label} must be a positive number or None; got {value!r}")
    for label in ("end_stop_stiffness", "end_stop_damping"):
        value = getattr(pto, label)
        if not (np.isfinite(value) and value >= 0):
            raise ValueError(f"PTO {pto.name!r}: {label} must be >= 0; got {value!r}")
    if pto.end_stop_stiffness > 0 and pto.stroke_limit is None:
        raise ValueError(f"PTO {pto.name!r}: an end stop (end_stop_stiffness) needs a stroke_limit")
    if pto.end_stop_damping > 0 and pto.end_stop_stiffness == 0:
        raise ValueError(f"PTO {pto.name!r}: end_stop_damping needs an end_stop_stiffness")


@dataclass(frozen=True)
class JointPTO:
    """A PTO acting on the coordinate of a one-DOF joint (revolute: torque [N m]; prismatic: force [N]).

    Parameters
    ----------
    name : str
    joint : str
        Name of a revolute or prismatic joint.
    damping : float
        Linear damping d [N m s/rad or N s/m] (the M4 paper's 6 N m s/rad, Eq. 50).
    stiffness : float
        Linear stiffness k [N m/rad or N/m].
    rest : float
        Joint coordinate where the spring force vanishes [rad or m].
    force_limit : float or None
        Largest |f| the controller can command [N m or N]: its force is saturated there; None for no limit.
    stroke_limit : float or None
        Largest |x - rest| [rad or m]; None for no limit. Beyond it acts the end stop, or, without one, the run
        stops (``PtoLimitExceeded``).
    end_stop_stiffness, end_stop_damping : float
        The end stop beyond ``stroke_limit``: a spring [N m/rad or N/m] on the excess stroke and a damper [N m s/rad
        or N s/m] while it is engaged; 0 for none.
    """

    name: str
    joint: str
    damping: float = 0.0
    stiffness: float = 0.0
    rest: float = 0.0
    force_limit: float | None = None
    stroke_limit: float | None = None
    end_stop_stiffness: float = 0.0
    end_stop_damping: float = 0.0

    def __post_init__(self) -> None:
        _check_gains(self.name, self.damping, self.stiffness)
        _check_limits(self)

    def stroke(self, model: Multibody, q: np.ndarray, state: KinematicState) -> tuple[float, np.ndarray]:
        """Stroke x(q) (the joint coordinate) and transmission g = dx/dq (a unit vector)."""
        names = model.velocity_names
        joint = model.joint(self.joint)
        if joint.kind not in ("revolute", "prismatic"):
            raise ValueError(
                f"PTO {self.name!r}: joint {self.joint!r} is {joint.kind}; "
                "a joint PTO needs a revolute or prismatic joint"
            )
        k = names.index(f"{joint.name}__{joint.labels[0]}")
        g = np.zeros(model.nv)
        g[k] = 1.0
        return float(q[model.coordinate_names.index(names[k])]), g


@dataclass(frozen=True)
class ActuatorPTO:
    """A linear actuator (hydraulic cylinder, linear motor) between a point on body A and a point on body B.

    Parameters
    ----------
    name : str
    body_a, body_b : str or None
        Bodies carrying the end points (None: the ground).
    point_a, point_b : array_like (3,)
        End points in the world frame at the reference configuration [m].
    damping, stiffness : float
        Linear damping [N s/m] and stiffness [N/m] along the actuator.
    rest_length : float or None
        Length where the spring force vanishes [m]; None: the length at the reference configuration.
    force_limit, stroke_limit : float or None
        Largest |f| [N] and largest |c - rest_length| [m]; None for no limit (see :class:`JointPTO`).
    end_stop_stiffness, end_stop_damping : float
        The end stop beyond ``stroke_limit`` [N/m, N s/m]; 0 for none.
    """

    name: str
    body_a: str | None
    point_a: np.ndarray
    body_b: str | None
    point_b: np.ndarray
    damping: float = 0.0
    stiffness: float = 0.0
    rest_length: float | None = None
    force_limit: float | None = None
    stroke_limit: float | None = None
    end_stop_stiffness: float = 0.0
    end_stop_damping: float = 0.0

    def __post_init__(self) -> None:
        _check_gains(self.name, self.damping, self.stiffness)
        _check_limits(self)
        for label in ("point_a", "point_b"):
            arr = np.asarray(getattr(self, label), dtype=float)
            if arr.shape != (3,):
                raise ValueError(f"PTO {self.name!r}: {label} must be 3 coordinates [m]; got {getattr(self, label)!r}")
            object.__setattr__(self, label, arr)
        if np.allclose(self.point_a, self.point_b):
            raise ValueError(f"PTO {self.name!r}: the two end points coincide; the actuator has no direction")
        if self.body_a == self.body_b:
            raise ValueError(f"PTO {self.name!r}: both ends are on {self.body_a!r}; the length would never change")
        if self.rest_length is None:
            object.__setattr__(self, "rest_length", float(np.linalg.norm(self.point_a - self.point_b)))

    def _point(self, model: Multibody, state: KinematicState, body: str | None, point: np.ndarray):
        if body is None:
            return point, np.zeros((3, model.nv))
        i = model.body_names.index(body)
        elastic = model.bodies[i].elastic
        if elastic is not None:  # the end rides on its node: the attachment pto:<name> of the flexible body
            name = f"pto:{self.name}"
            if name not in elastic.attachments:
                raise ValueError(
                    f"PTO {self.name!r}: its end on the flexible body {body!r} needs the body's attachment {name!r} "
                    f"(a point of its structure); attachments: {sorted(elastic.attachments)}"
                )
            if not np.allclose(elastic.attachments[name].point, point, rtol=0, atol=1e-9):
                raise ValueError(
                    f"PTO {self.name!r}: its end {np.round(point, 9).tolist()} m on {body!r} is not where the "
                    f"attachment {name!r} is, {np.round(elastic.attachments[name].point, 9).tolist()} m"
                )
            return state.point(i, name)
        r_body = point - model.bodies[i].center_of_mass  # body axes are the world axes at the reference pose
        position = state.position[i] + state.rotation[i] @ r_body
        s = model.cart_start[i]
        jac = state.B[s : s + 3] - state.rotation[i] @ hat(r_body) @ state.B[s + 3 : s + 6]
        return position, jac

    def stroke(self, model: Multibody, q: np.ndarray, state: KinematicState) -> tuple[float, np.ndarray]:
        """Length c(q) [m] and transmission g = dc/dq (so that c_dot = g' v) (point-absorber paper Eqs. 1, 34)."""
        pa, ja = self._point(model, state, self.body_a, self.point_a)
        pb, jb = self._point(model, state, self.body_b, self.point_b)
        d = pa - pb
        length = float(np.linalg.norm(d))
        return length, (ja - jb).T @ (d / length)

    @property
    def rest(self) -> float:
        """Length at zero spring force [m]."""
        assert self.rest_length is not None
        return self.rest_length


PTO = JointPTO | ActuatorPTO
