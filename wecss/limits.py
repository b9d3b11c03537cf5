"""Limits on the size of the work a user asks for, each with its override: beyond a limit a request is refused
before any work, with a message that names the field, the value received, the limit and how to go beyond it.

They catch typing slips that would otherwise look like hangs (issue 31: an MPC horizon of 5,000 control periods
filled 1.7 GB in 80 s without a solve; a 300 x 300 sweep grid spent minutes validating its cases in silence; the
reference solver on a PTO damping of 1e7 N m s/rad would need hundreds of millions of evaluations). A limit is a
judgement about what is usually meant, not a ceiling of the code: every one has an override.
"""

from __future__ import annotations

MPC_PLANNED_FORCES: int = 2000
"""Largest number of forces one MPC plan may hold (``horizon`` x PTOs): its dense prediction matrices grow as the
square of it (2000 forces: 32 MB each) and a solve as up to its cube. Override: the controller parameter
``allow_large = true``."""

SWEEP_CASES: int = 10_000
"""Largest number of cases of a sweep (each case's scene is validated before the first runs, about 1 ms each, and
each case is a file). Override: ``allow_large = true`` in the sweep file's ``[sweep]`` table
(``Sweep(..., allow_large=True)``)."""

SWEEP_ANNOUNCE_CASES: int = 1000
"""A sweep with more cases than this says its size on standard error before validating them."""

REFERENCE_EVALUATIONS: int = 2_000_000
"""Largest number of right-hand-side evaluations the reference solver (an explicit Runge-Kutta method) may need:
about 0.4 ms each on the test scenes, so some 15 minutes. Override: ``solver.allow_large = true``."""


class LimitError(ValueError):
    """A request beyond one of the limits of :mod:`wecss.limits` (the message names the override)."""


def beyond(field: str, value: object, limit: object, why: str, override: str) -> str:
    """The message of a refusal: ``field`` got ``value``, beyond ``limit``, ``why`` it matters, and the
    ``override`` that runs it anyway."""
    return f"{field} = {value} is beyond the limit of {limit} ({why}); {override} to run it anyway"
