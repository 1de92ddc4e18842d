"""Chebyshev interpolation on Lobatto nodes, in one variable (several outputs) and in two (a tensor series):
the machinery the sweep's interpolants share (:mod:`.similarity`, :mod:`.plane`)."""

from __future__ import annotations

import numpy as np
from numpy.polynomial.chebyshev import chebval

#: Points evaluated per matrix product of a :class:`Series` or :class:`Tensor` (a fixed width: a point's value
#: does not depend on how many are evaluated with it).
EVAL_BLOCK = 8192
#: Trailing rows and columns of a :class:`Tensor`'s coefficients are dropped from the evaluated series while
#: the sum of the dropped magnitudes (a bound on the change, |T_k| <= 1) stays below TRUNCATE x target.
TRUNCATE = 0.01


def lobatto(a: float, b: float, n: int) -> np.ndarray:
    """n Chebyshev-Lobatto points on [a, b], from b down to a."""
    return 0.5 * (a + b) + 0.5 * (b - a) * np.cos(np.pi * np.arange(n) / (n - 1))


class Series:
    """Chebyshev series in u on [a, b] of several outputs, interpolating values at Lobatto points.

    The coefficients come from a type-I DCT of the values (exact interpolation at the points
    cos(pi j / (N - 1)), in O(N log N)); all outputs are evaluated by one Clenshaw recurrence.
    """

    def __init__(self, a: float, b: float, values: dict):
        self.a, self.b, self.keys = a, b, tuple(values)
        self.values = np.stack([values[k] for k in self.keys], axis=1)  # (N, outputs), from u = b down to a
        self.nodes = lobatto(a, b, self.values.shape[0])
        from scipy.fft import dct  # imported on use: a sweep without interpolants does not pay for it

        coef = dct(self.values, type=1, axis=0) / (self.values.shape[0] - 1)
        coef[0] /= 2.0
        coef[-1] /= 2.0
        self.coef = coef

    def _local(self, u):
        """u mapped onto the series' variable t in [-1, 1]."""
        return (2.0 * np.asarray(u, dtype=float) - (self.a + self.b)) / (self.b - self.a)

    def __call__(self, u, keys=None) -> dict:
        """The outputs (all, or ``keys``) at u: sum_k c_k T_k(t) as one matrix product per block of
        EVAL_BLOCK points (padded, so a point's value does not depend on how many are evaluated with it), a
        quarter of Clenshaw's time on 10^5 points."""
        keys = self.keys if keys is None else tuple(keys)
        coef = np.ascontiguousarray(self.coef[:, [self.keys.index(k) for k in keys]].T)  # (outputs, N)
        t = np.atleast_1d(self._local(u))
        out = np.empty((len(keys), t.size))
        (block, basis), product = _block_work(t.size, coef.shape[1]), np.empty((len(keys), EVAL_BLOCK))
        for start in range(0, t.size, EVAL_BLOCK):
            stop = min(start + EVAL_BLOCK, t.size)
            block[:stop - start] = t[start:stop]
            block[stop - start:] = 0.0
            np.matmul(coef, chebyshev_matrix(block, coef.shape[1], basis), out=product)
            out[:, start:stop] = product[:, :stop - start]
        return dict(zip(keys, out))

    def value(self, key: str, u):
        """One output at u (a root search needs no others)."""
        return chebval(self._local(u), self.coef[:, self.keys.index(key)])

    def column(self, key: str) -> np.ndarray:
        """The values of one output at the nodes (from u = b down to a)."""
        return self.values[:, self.keys.index(key)]


def _block_work(points: int, terms: int) -> tuple:
    """(a block of EVAL_BLOCK points, its Chebyshev matrix (terms, EVAL_BLOCK)): an evaluation's work arrays, made once
    per call and reused by every block (empty for no points).  A block's matrix is megabytes: allocated afresh for each
    block, it page-faulted whenever the allocator handed back new memory (a sweep's evaluation ran 2-3x its time
    alone)."""
    width = EVAL_BLOCK if points else 0
    return np.zeros(width), np.empty((terms, width))


def chebyshev_matrix(t, n: int, out: np.ndarray | None = None) -> np.ndarray:
    """T_0..T_(n-1) at t, shape (n, len(t)) (into ``out`` when given, an array of that shape)."""
    out = np.empty((n, t.size)) if out is None else out
    out[0] = 1.0
    if n > 1:
        out[1] = t
    two_t = 2.0 * t
    for k in range(2, n):
        np.multiply(two_t, out[k - 1], out=out[k])
        out[k] -= out[k - 2]
    return out


def _kept(size: np.ndarray, budget: float) -> tuple[int, int]:
    """(rows, columns) of ``size`` (coefficient magnitudes) to keep: trailing rows, then trailing columns, are
    dropped while the dropped magnitudes sum to at most ``budget`` (half of it for each direction)."""
    rows = size.shape[0]
    while rows > 1 and size[rows - 1:].sum() <= 0.5 * budget:
        rows -= 1
    dropped, cols = size[rows:].sum(), size.shape[1]
    while cols > 1 and dropped + size[:rows, cols - 1:].sum() <= budget:
        cols -= 1
    return rows, cols


class Tensor:
    """A tensor Chebyshev series in (a, b) on [lo, hi] x [0, 1] (b already mapped), of several outputs,
    interpolating values on the Lobatto grid (values: (n_a, n_b, outputs), both axes from the top down).

    Its tails (the last two coefficients in each direction, summed over the other) estimate how well it
    resolves each direction; negligible trailing coefficients are dropped (:func:`_kept`, TRUNCATE x
    ``target`` in all).
    """

    def __init__(self, lo: float, hi: float, values: np.ndarray, target: float):
        self.lo, self.hi = lo, hi
        from scipy.fft import dctn  # imported on use, as dct

        coef = dctn(values, type=1, axes=(0, 1)) / ((values.shape[0] - 1) * (values.shape[1] - 1))
        coef[[0, -1]] /= 2.0
        coef[:, [0, -1]] /= 2.0
        self.tails = (float(np.abs(coef[-2:]).max(axis=2).sum()), float(np.abs(coef[:, -2:]).max(axis=2).sum()))
        size = np.abs(coef).max(axis=2)
        rows, cols = _kept(size, TRUNCATE * target)
        self.coef = np.ascontiguousarray(coef[:rows, :cols].transpose(2, 0, 1))

    def __call__(self, a, b01) -> np.ndarray:
        """Values at (a, b01), b01 in [0, 1]: shape (outputs, len(a)).

        sum_ij c_ij T_i(a) T_j(b) as (C T_b) summed against T_a: one matrix product for all outputs, in
        blocks of EVAL_BLOCK points (the last one padded), so that a point's value does not depend on how
        many are evaluated with it (a BLAS product of another width may round differently).
        """
        outputs, n_a, n_b = self.coef.shape
        flat = self.coef.reshape(outputs * n_a, n_b)
        out = np.empty((outputs, a.size))
        (tb, basis_b), (ta, basis_a) = _block_work(a.size, n_b), _block_work(a.size, n_a)
        product = np.empty((outputs * n_a, EVAL_BLOCK))
        for start in range(0, a.size, EVAL_BLOCK):
            stop = min(start + EVAL_BLOCK, a.size)
            ta[:stop - start] = (2.0 * a[start:stop] - (self.lo + self.hi)) / (self.hi - self.lo)
            tb[:stop - start] = 2.0 * b01[start:stop] - 1.0
            ta[stop - start:] = tb[stop - start:] = 0.0
            np.matmul(flat, chebyshev_matrix(tb, n_b, basis_b), out=product)
            values = np.einsum("kan,an->kn", product.reshape(outputs, n_a, -1), chebyshev_matrix(ta, n_a, basis_a))
            out[:, start:stop] = values[:, :stop - start]
        return out
