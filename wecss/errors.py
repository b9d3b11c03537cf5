"""The base classes of what wecss raises and warns, below every package (floor 0).

``WecssWarning`` is the base of every warning wecss issues, so that users (and the test suite, which turns them into
errors) can filter the package's own warnings at once: ``warnings.simplefilter("error", WecssWarning)`` or
``-W error::wecss.errors.WecssWarning``.
"""

from __future__ import annotations


class WecssWarning(UserWarning):
    """Base class of the warnings wecss issues (the test suite turns them into errors)."""
