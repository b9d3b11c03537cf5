"""Stress fields of a flexible body's members, recorded chunk by chunk: fatigue life, extremes and RMS at every
stress point without holding the field's time series.

Each chunk of modal coordinates (their accelerations and the 12 rigid-motion load coordinates optional) becomes the
signed von Mises stress at every point of a :class:`~wecss.structure.StressModes` (three matrix products,
``StressModes.stresses``); the chunk feeds a :class:`~wecss.results.StreamingRainflow` (one channel per point) and
running extremes and sums of squares, and is dropped. Memory: the residue of each point's rainflow count, a few
numbers per point, and the time series of the points asked for (every ``every``-th sample). The fatigue life of a
point is :func:`~wecss.results.life_years` of its Miner sum over the record's duration (paper 003, Eq. 55
generalised), the count that of :func:`~wecss.results.rainflow_cycles` on the whole record.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr

from ..attributes import apply_attrs
from ..structure import StressModes, StressPoint
from ._fatigue import life_years
from ._sn_curves import SNCurve, sn_curve
from ._streaming_rainflow import StreamingRainflow

N_RIGID = 12
"""Rigid-motion load coordinates per sample (``wecss.structure.RIGID_LOADS``)."""


def point_names(points: Sequence[StressPoint]) -> list[str]:
    """The points' names when they are distinct, else ``<member>@<station>.<name>`` (as ``FlexibleBody`` names
    its fibres).

    Raises
    ------
    ValueError
        If even the long names repeat (two points at one place with one name).
    """
    names = [p.name for p in points]
    if len(set(names)) == len(names) and all(names):
        return names
    names = [f"{p.member}@{p.station:.6g}.{p.name}" for p in points]
    if len(set(names)) != len(names):
        repeated = sorted({n for n in names if names.count(n) > 1})
        raise ValueError(f"stress points repeat (same member, station and name): {repeated[:5]}; name them apart")
    return names


class StressFieldRecorder:
    """Fatigue life, extremes and RMS of the signed von Mises stress at every point of a body, fed in chunks.

    Parameters
    ----------
    modes : StressModes
        The body's stress modes (``FlexibleBody.stresses``: hot spots, then every node's default fibres); their
        stresses hold each point's SCF already.
    dt : float
        Time between samples [s].
    curve : str or SNCurve
        S-N curve of the Miner sums (default the paper's Table 5).
    keep : sequence of str, optional
        Names of points whose signed von Mises time series is kept (in the result as
        ``signed_von_mises_series``); memory grows with the record for these only.
    every : int
        Keep every ``every``-th sample of those series (from the first) (default 1).
    motion : bool
        Add the loads of the frame's rotation on the elastic displacements when the rigid-motion coordinates are
        given (``StressModes.stresses``); False for a quasi-static response solved without them (default True).

    Raises
    ------
    ValueError
        On a step that is not positive, an unknown curve or kept point, or ``every`` below 1.

    Examples
    --------
    >>> body = wecss.devices.load("notc-10kw").flexible_body("arm")      # doctest: +SKIP
    >>> recorder = StressFieldRecorder(body.stresses, dt=0.01)           # doctest: +SKIP
    >>> for q in chunks:                                                 # doctest: +SKIP
    ...     recorder.update(q)                   # (n, n_modes) modal coordinates
    >>> recorder.result()                        # Dataset on dim "point"  # doctest: +SKIP
    """

    def __init__(
        self,
        modes: StressModes,
        dt: float,
        curve: str | SNCurve = "paper-003-table-5",
        keep: Sequence[str] = (),
        every: int = 1,
        motion: bool = True,
    ) -> None:
        if not isinstance(modes, StressModes):
            raise ValueError(f"modes must be a wecss.structure.StressModes, got {type(modes).__name__}")
        if not (isinstance(dt, int | float) and np.isfinite(dt) and dt > 0.0):
            raise ValueError(f"the time step dt must be a positive number of seconds, got {dt!r}")
        if isinstance(every, bool) or not isinstance(every, int | np.integer) or every < 1:
            raise ValueError(f"every must be a whole number of at least 1, got {every!r}")
        self.modes = modes
        self.dt = float(dt)
        self.curve = sn_curve(curve)
        self.names = point_names(modes.points)
        if isinstance(keep, str):
            keep = [keep]
        unknown = [k for k in keep if k not in self.names]
        if unknown:
            raise ValueError(f"points to keep {unknown} are not among the {len(self.names)} points, e.g. "
                             f"{self.names[:4]}")  # fmt: skip
        self.keep = [self.names.index(k) for k in keep]
        self.every = int(every)
        if not isinstance(motion, bool | np.bool_):
            raise ValueError(f"motion must be True or False, got {motion!r}")
        self.motion = bool(motion)
        n = len(modes.points)
        if n == 0:
            raise ValueError("the stress modes have no points; give StressModes with at least one StressPoint")
        self.counter = StreamingRainflow(n, self.curve)
        """The points' rainflow counter (one channel per point, in the order of ``modes.points``)."""
        self._max = np.full(n, -np.inf)
        self._min = np.full(n, np.inf)
        self._squares = np.zeros(n)
        self._series: list[np.ndarray] = []
        self._seen = 0

    @property
    def n_modes(self) -> int:
        """Modal coordinates per sample."""
        return int(self.modes.normal.shape[1])

    @property
    def n_samples(self) -> int:
        """Samples recorded so far."""
        return self._seen

    def update(
        self,
        q: np.ndarray,
        q_ddot: np.ndarray | None = None,
        rigid: np.ndarray | None = None,
        q_dot: np.ndarray | None = None,
        omega: np.ndarray | None = None,
    ) -> None:
        """Record the next samples.

        Parameters
        ----------
        q : array_like (n, n_modes)
            Modal coordinates [1].
        q_ddot : array_like (n, n_modes), optional
            Their accelerations [1/s^2] (the modes' inertia loads).
        rigid : array_like (n, 12), optional
            The rigid-motion load coordinates (``wecss.structure.RIGID_LOADS``); with them the loads of the
            frame's rotation on the elastic displacements.
        q_dot, omega : array_like (n, n_modes) and (n, 3), optional
            The modal rates [1/s] and the frame's angular velocity [rad/s] (body axes), both or neither: the
            Coriolis loads of the elastic motion.

        Raises
        ------
        ValueError
            If a shape is not the one above, a value is not finite, or one of ``q_dot`` and ``omega`` is given
            without the other.
        """
        q = self._rows("q", q, self.n_modes, None)
        n = q.shape[0]
        q_ddot = None if q_ddot is None else self._rows("q_ddot", q_ddot, self.n_modes, n)
        rigid = None if rigid is None else self._rows("rigid", rigid, N_RIGID, n)
        q_dot = None if q_dot is None else self._rows("q_dot", q_dot, self.n_modes, n)
        omega = None if omega is None else self._rows("omega", omega, 3, n)
        if n == 0:
            return
        signed = self.modes.stresses(q, q_ddot, rigid, q_dot, omega, motion=self.motion)["signed_von_mises"]
        self.counter.update(signed)
        np.maximum(self._max, signed.max(axis=0, initial=-np.inf), out=self._max)
        np.minimum(self._min, signed.min(axis=0, initial=np.inf), out=self._min)
        self._squares += np.einsum("ij,ij->j", signed, signed)
        if self.keep:
            first = (-self._seen) % self.every
            self._series.append(signed[first :: self.every, self.keep].copy())
        self._seen += n

    @staticmethod
    def _rows(name: str, value: np.ndarray, width: int, n: int | None) -> np.ndarray:
        out = np.asarray(value, dtype=float)
        if out.ndim != 2 or out.shape[1] != width or (n is not None and out.shape[0] != n):
            rows = "n" if n is None else str(n)
            raise ValueError(f"{name} must be ({rows}, {width}) [one row per sample], got shape {out.shape}")
        if not np.all(np.isfinite(out)):
            raise ValueError(f"{name} holds NaN or infinite values")
        return out

    def duration(self) -> float:
        """The record's duration, (n_samples - 1) dt [s] (from its first sample to its last)."""
        return (self._seen - 1) * self.dt

    def result(self) -> xr.Dataset:
        """The record so far as a Dataset on dim ``point`` (its residue closed as half cycles).

        Variables: ``damage`` [1], ``life_years`` [year] (``inf`` where nothing was counted),
        ``signed_von_mises_max`` and ``_min`` [Pa], ``von_mises_rms`` [Pa], and ``signed_von_mises_series``
        (series_time, series_point) [Pa] for the kept points. Coordinates: ``member``, ``station`` [m], ``y``, ``z``
        [m] and ``scf`` [1] per point. Attributes: the S-N curve, the duration [s], the step [s], samples.

        Raises
        ------
        ValueError
            Before two samples (no duration).
        """
        if self._seen < 2:
            raise ValueError(f"a record needs at least two samples for a duration, got {self._seen}")
        duration = self.duration()
        points = self.modes.points
        damage = self.counter.damage()
        life = np.array([life_years(float(d), duration) for d in damage])
        coords = {
            "point": ("point", np.array(self.names, dtype=object), {"long_name": "stress point (member.spot or "
                      "member@station.fibreK)"}),
            "member": ("point", np.array([p.member for p in points], dtype=object)),
            "station": ("point", np.array([p.station for p in points], dtype=float)),
            "y": ("point", np.array([p.y for p in points], dtype=float)),
            "z": ("point", np.array([p.z for p in points], dtype=float)),
            "scf": ("point", np.array([p.scf for p in points], dtype=float)),
        }  # fmt: skip
        data: dict[str, tuple[str | tuple[str, ...], np.ndarray]] = {
            "damage": ("point", damage),
            "life_years": ("point", life),
            "signed_von_mises_max": ("point", self._max.copy()),
            "signed_von_mises_min": ("point", self._min.copy()),
            "von_mises_rms": ("point", np.sqrt(self._squares / self._seen)),
        }
        if self.keep:
            series = np.concatenate(self._series) if self._series else np.zeros((0, len(self.keep)))
            coords["series_point"] = ("series_point", np.array([self.names[k] for k in self.keep], dtype=object))
            coords["series_time"] = ("series_time", self.every * self.dt * np.arange(series.shape[0]))
            data["signed_von_mises_series"] = (("series_time", "series_point"), series)
        attrs = {
            "sn_curve": self.curve.name,
            "sn_curve_source": self.curve.source,
            "duration": duration,
            "dt": self.dt,
            "n_samples": self._seen,
            "rainflow": "ASTM E1049-85 as the rainflow package counts it, streamed; residue as half cycles",
            "stress": "signed von Mises stress (paper 003, Eq. 53), the point's SCF applied",
        }
        return apply_attrs(xr.Dataset(data, coords=coords, attrs=attrs))

    def __repr__(self) -> str:
        return f"StressFieldRecorder({len(self.names)} points, {self.n_modes} modes, {self._seen} samples)"
