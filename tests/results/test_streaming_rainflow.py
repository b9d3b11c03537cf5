"""The streamed rainflow count against ``rainflow_cycles`` and ``miner_damage`` on the whole record: the same cycles
(range and count) and Miner sums to 1e-12 relative, whatever the chunks; reversals across chunk boundaries; the
residue (the counter's memory) bounded over a million samples; bad inputs."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from wecss.results import SNCurve, StreamingRainflow, _streaming_rainflow, miner_damage, rainflow_cycles
from wecss.results._streaming_rainflow import _count, _loop, _python_count

pytest.importorskip("rainflow")

MPA = 1e6
RTOL = 1e-12


def _series(kind: str, n: int, channels: int, rng: np.random.Generator) -> np.ndarray:
    if kind == "normal":
        return 50 * MPA * rng.normal(size=(n, channels))
    if kind == "walk":
        return MPA * np.cumsum(rng.normal(size=(n, channels)), axis=0)
    if kind == "integers":  # many repeated values and plateaus of equal neighbours
        return MPA * rng.integers(-3, 4, size=(n, channels)).astype(float)
    if kind == "plateaus":  # runs of equal samples of random lengths
        values = rng.normal(size=(n, channels))
        runs = np.repeat(values[: n // 4 + 1], rng.integers(1, 8, size=n // 4 + 1), axis=0)[:n]
        return 20 * MPA * np.vstack([runs, np.zeros((n - runs.shape[0], channels))])
    if kind == "exponential":
        return 10 * MPA * rng.exponential(size=(n, channels)) ** 2
    if kind == "sine":
        t = np.arange(n)[:, None] * 0.05
        return 80 * MPA * np.sin(t * rng.uniform(0.5, 2.0, channels)) + MPA * rng.normal(size=(n, channels))
    raise ValueError(kind)


def _chunks(x: np.ndarray, rng: np.random.Generator, largest: int) -> list[np.ndarray]:
    out, i = [], 0
    while i < x.shape[0]:
        k = int(rng.integers(0, largest + 1))  # empty chunks too
        out.append(x[i : i + k])
        i += k
    return out


def _fed(x: np.ndarray, chunks: list[np.ndarray], **options) -> StreamingRainflow:
    counter = StreamingRainflow(x.shape[1], keep_cycles=True, **options)
    for chunk in chunks:
        counter.update(chunk)
    counter.finish()
    return counter


def _sorted(ranges: np.ndarray, counts: np.ndarray) -> np.ndarray:
    rows = np.column_stack([ranges, counts])
    return rows[np.lexsort((rows[:, 1], rows[:, 0]))]


def assert_counts_equal(counter: StreamingRainflow, x: np.ndarray) -> float:
    """Cycles and Miner sums of every channel against the whole-record count; returns the largest relative error."""
    worst = 0.0
    damage = counter.damage()
    for j in range(x.shape[1]):
        expected, got = rainflow_cycles(x[:, j]), counter.cycles(j)
        a, b = _sorted(expected.ranges, expected.counts), _sorted(got.ranges, got.counts)
        assert a.shape == b.shape, f"channel {j}: {a.shape[0]} cycles expected, {b.shape[0]} counted"
        np.testing.assert_allclose(b, a, rtol=RTOL, atol=0.0)
        d = miner_damage(expected)
        assert damage[j] == pytest.approx(d, rel=RTOL, abs=0.0)
        if d > 0:
            worst = max(worst, abs(damage[j] - d) / d)
    return worst


@pytest.mark.parametrize("kind", ["normal", "walk", "integers", "plateaus", "exponential", "sine"])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_random_chunks_count_what_the_whole_record_counts(kind, seed):
    rng = np.random.default_rng(seed)
    x = _series(kind, int(rng.integers(50, 3000)), 4, rng)
    counter = _fed(x, _chunks(x, rng, largest=int(rng.integers(1, 400))))
    assert counter.n_samples == x.shape[0]
    assert_counts_equal(counter, x)


def test_one_chunk_equals_one_sample_chunks():
    rng = np.random.default_rng(7)
    x = _series("integers", 600, 3, rng) + _series("walk", 600, 3, rng)
    whole = _fed(x, [x])
    single = _fed(x, [x[i : i + 1] for i in range(x.shape[0])])
    np.testing.assert_allclose(single.damage(), whole.damage(), rtol=RTOL, atol=0.0)
    for j in range(3):
        a, b = whole.cycles(j), single.cycles(j)
        np.testing.assert_array_equal(_sorted(a.ranges, a.counts), _sorted(b.ranges, b.counts))


@pytest.mark.parametrize(
    "record",
    [
        [0.0, 2.0, 2.0, 2.0, -1.0, -1.0, 3.0, 0.0, 0.0, 0.0, 4.0],  # plateaus at peaks and valleys
        [1.0, 1.0, 1.0, 2.0, 0.0, 3.0, 3.0],  # a flat start, a flat end
        [5.0, 5.0, 5.0, 5.0, 5.0],  # constant: no cycles
        [0.0, 1.0, 0.0, 1.0, 0.0, 1.0],  # a reversal at every sample
        [0.0, 3.0, 1.0, 2.0, 2.0, 1.5, 4.0, -2.0, -2.0],
        [1.0, 2.0],  # two samples: no turning point but the first (as the rainflow package)
        [1.0, 2.0, 1.0],
    ],
)
def test_every_split_of_a_short_record_counts_the_same(record):
    x = np.asarray(record)[:, None] * MPA
    for cut in range(x.shape[0] + 1):
        for second in range(cut, x.shape[0] + 1):
            counter = _fed(x, [x[:cut], x[cut:second], x[second:]])
            assert_counts_equal(counter, x)


@settings(max_examples=150, deadline=None)
@given(
    values=st.lists(st.integers(-4, 4), min_size=2, max_size=60),
    cuts=st.lists(st.integers(0, 60), max_size=6),
)
def test_any_record_in_any_chunks_counts_what_the_package_counts(values, cuts):
    x = np.asarray(values, dtype=float)[:, None] * MPA
    edges = [0, *sorted(c for c in cuts if c <= x.shape[0]), x.shape[0]]
    assert_counts_equal(_fed(x, [x[a:b] for a, b in itertools.pairwise(edges)]), x)


def test_curves_and_scf_per_channel_give_miners_sums():
    rng = np.random.default_rng(3)
    x = _series("normal", 2000, 3, rng)
    steep = SNCurve("single-slope", (4.0,), (13.0,), (), "test")
    scf = np.array([1.0, 1.5, 2.5])
    counter = _fed(x, _chunks(x, rng, 300), curves=["paper-003-table-5", steep], scf=scf)
    for curve in ("paper-003-table-5", steep):
        expected = [miner_damage(rainflow_cycles(x[:, j]), curve, float(scf[j])) for j in range(3)]
        np.testing.assert_allclose(counter.damage(curve), expected, rtol=RTOL, atol=0.0)


def test_damage_midway_is_the_record_so_far():
    rng = np.random.default_rng(4)
    x = _series("sine", 1500, 2, rng)
    counter = StreamingRainflow(2)
    counter.update(x[:700])
    midway = counter.damage()
    expected = [miner_damage(rainflow_cycles(x[:700, j])) for j in range(2)]
    np.testing.assert_allclose(midway, expected, rtol=RTOL, atol=0.0)
    counter.update(x[700:])  # asking did not change the state
    expected = [miner_damage(rainflow_cycles(x[:, j])) for j in range(2)]
    np.testing.assert_allclose(counter.damage(), expected, rtol=RTOL, atol=0.0)


@pytest.mark.parametrize("kind", ["walk", "normal"])
def test_the_residue_stays_short_over_a_million_samples(kind):
    """The memory held is the residue: measured 8 to 18 turning points after 1e6 samples of a Gaussian random walk
    and of white noise (seeds 2, 5); the bound is ten times that. (1e5 samples without numba: 4 us a sample.)"""
    rng = np.random.default_rng(5)
    counter = StreamingRainflow(2)
    last = np.zeros(2)
    chunks = 1 if _loop() is _python_count else 20
    for _ in range(chunks):
        chunk = _series(kind, 50_000, 2, rng)
        if kind == "walk":  # continue the walk from the last value
            chunk, last = last + chunk, last + chunk[-1]
        counter.update(chunk)
    assert counter.n_samples == chunks * 50_000
    assert counter.residue_lengths.max() < 200
    assert counter.nbytes < 2 * 200 * 8 + 1000  # the stack is trimmed to the residue after each chunk


@pytest.mark.parametrize("kind", ["integers", "plateaus", "sine", "walk"])
def test_the_loops_agree_sample_by_sample_and_on_candidates(kind):
    """The compiled loop (when numba is installed), the Python loop on every sample and the Python loop on the
    candidate turning points leave the same state (the last step's direction, not its size) and close the same
    cycles."""
    rng = np.random.default_rng(6)
    rows = np.ascontiguousarray(_series(kind, 400, 3, rng).T)
    results = []
    for fn in {_loop(), _count, _python_count}:
        x, d, length = np.zeros(3), np.zeros(3), np.zeros(3, dtype=np.int64)
        stack = np.zeros((3, 402))
        out = np.zeros(1300), np.zeros(1300), np.zeros(1300, dtype=np.int64)
        k = 0
        for start, end in ((0, 150), (150, 151), (151, 400), (400, 400)):  # 150, 1, 249 and 0 samples
            chunk = np.ascontiguousarray(rows[:, start:end])
            k += fn(chunk, start, False, x, d, stack, length, *(o[k:] for o in out))
        order = np.lexsort((out[0][:k], out[2][:k]))
        residues = [stack[j, : length[j]] for j in range(3)]
        # the last step's direction is the state; its size differs on the candidates
        results.append((k, x, np.sign(d), length, *residues, *(o[:k][order] for o in out)))
    for other in results[1:]:
        for a, b in zip(results[0], other, strict=True):
            np.testing.assert_array_equal(a, b)


def test_the_python_path_counts_what_the_package_counts(monkeypatch):
    monkeypatch.setattr(_streaming_rainflow, "_loop", lambda: _python_count)
    rng = np.random.default_rng(8)
    for kind in ("integers", "plateaus", "sine", "exponential"):
        x = _series(kind, 1500, 3, rng)
        assert_counts_equal(_fed(x, _chunks(x, rng, largest=200)), x)


def test_bad_inputs_say_what_is_accepted():
    counter = StreamingRainflow(2)
    with pytest.raises(ValueError, match=r"\(n_samples, 2\)"):
        counter.update(np.zeros((5, 3)))
    with pytest.raises(ValueError, match="NaN"):
        counter.update(np.array([[0.0, np.nan]]))
    with pytest.raises(ValueError, match="keep_cycles=True"):
        counter.cycles(0)
    with pytest.raises(ValueError, match="not 'other'"):
        counter.damage("other")
    counter.finish()
    with pytest.raises(ValueError, match="finished"):
        counter.update(np.zeros((1, 2)))
    with pytest.raises(ValueError, match="at least 1"):
        StreamingRainflow(0)
    with pytest.raises(ValueError, match="scf"):
        StreamingRainflow(2, scf=[1.0, -1.0])
    with pytest.raises(ValueError, match="unknown S-N curve"):
        StreamingRainflow(2, curves="nope")
    with pytest.raises(ValueError, match=r"channel must be .* \[0, 2\)"):
        StreamingRainflow(2, keep_cycles=True).cycles(2)
