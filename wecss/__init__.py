"""wecss: time-domain dynamics, linear models and PTO control of multi-body wave energy converters."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("wecss")
except PackageNotFoundError:  # pragma: no cover - running from a source tree that is not installed
    __version__ = "0+unknown"
