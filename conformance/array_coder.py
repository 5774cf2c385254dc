"""Coded arrays of wavelet grids (spec 5.6, 5.7, 5.10), written from the text alone.

Enough of the encoder's side for hand-built vectors: the 16-ary symbol models of
5.6, arrays without prediction (5.7.1 to 5.7.3, with a way to write an escape
prefix of any length), and the bit strings of the baseline mode (5.10). It shares
no code with the reference encoder.
"""
from pm_coder import PROBABILITY_ONE, RangeEncoder

HALF = PROBABILITY_ONE // 2
CUM_START = [0, 16352, 24528, 28616, 30660, 31682, 32193, 32448, 32576, 32640, 32672, 32688, 32696,
             32700, 32702, 32703]


class SymbolModel:
    """spec 5.6: cum[0..15] and count."""

    def __init__(self):
        self.cum = list(CUM_START)
        self.count = 0

    def start(self, i):
        return (1 << 15) if i == 16 else self.cum[i] + 4 * i


def encode_symbol(rc, model, s):
    """The encoder's side of spec 5.6 decode_symbol()."""
    r = rc.range >> 15
    rc.low += model.start(s) * r
    rc.range = (model.start(s + 1) - model.start(s)) * r if s < 15 else rc.range - model.start(15) * r
    w = 5 if model.count < 64 else 7
    for i in range(1, 16):
        if i > s:
            model.cum[i] += (32704 - model.cum[i]) >> w
        else:
            model.cum[i] -= model.cum[i] >> w
    model.count = min(model.count + 1, 64)
    rc._normalize()


class ArrayContexts:
    """spec 5.7.1."""

    def __init__(self):
        self.block = [HALF] * 8
        self.zero = [HALF] * 10
        self.sign = [HALF] * 3
        self.magnitude = [[HALF] * 12 for _ in range(10)]
        self.first_low_bit = [[HALF] * 12 for _ in range(10)]
        self.level = [SymbolModel() for _ in range(10)]


def magnitude_class(a):
    """spec 5.7.3 step 1."""
    if a == 0:
        return 0
    k = 1
    while k < 9 and a > (1 << k):
        k += 1
    return k


def encode_line(values, prefix_bits=None):
    """A 1-D array without prediction or skipped positions, one block (at most 64
    values, 5.7.2), as one range-coded string. `prefix_bits` = (index, n) writes n
    one bits as the escape prefix of that value and stops there (an invalid string).
    A value None is a skipped position (symbol 0, nothing coded)."""
    assert len(values) <= 64
    rc, ctx = RangeEncoder(), ArrayContexts()
    rc.bit(ctx.block, 0, 1 if any(values) else 0)
    left = 0
    for i, v in enumerate(values if any(values) else []):
        if v is None:
            left = 0
            continue
        k = magnitude_class(2 * abs(left))
        rc.bit(ctx.zero, k, 1 if v else 0)
        if v:
            rc.bit(ctx.sign, 0 if left == 0 else 1 if left > 0 else 2, 1 if v < 0 else 0)
            m = abs(v)
            encode_symbol(rc, ctx.level[k], min(m - 1, 15))
            if m >= 16 or (prefix_bits and prefix_bits[0] == i):
                if prefix_bits and prefix_bits[0] == i:
                    for j in range(prefix_bits[1]):
                        rc.bit(ctx.magnitude[k], min(j, 11), 1)
                    return rc.finish()
                e = m - 15
                n = e.bit_length() - 1
                for j in range(n):
                    rc.bit(ctx.magnitude[k], min(j, 11), 1)
                rc.bit(ctx.magnitude[k], min(n, 11), 0)
                if n > 0:
                    rc.bit(ctx.first_low_bit[k], min(n, 11), (e >> (n - 1)) & 1)
                    rc.direct(e & ((1 << (n - 1)) - 1), n - 1)
        left = v
    return rc.finish()


def weighted_long_prefix():
    """spec 5.7.5: the first position of a weighted array (class 0, sign context 0) with
    39 one bits of magnitude prefix: an invalid string."""
    rc = RangeEncoder()
    zero, sign, magnitude = [HALF] * 20, [HALF] * 3, [HALF] * 12
    rc.bit(zero, 0, 1)
    rc.bit(sign, 0, 0)
    for j in range(39):
        rc.bit(magnitude, min(j, 11), 1)
    return rc.finish()


class BitWriter:
    """spec 5.10: bits from the most significant of each byte; fields most significant first."""

    def __init__(self):
        self.bits = []

    def put(self, value, n):
        self.bits += [(value >> (n - 1 - i)) & 1 for i in range(n)]

    def bytes(self, pad=0):
        bits = self.bits + [pad] * (-len(self.bits) % 8)
        return bytes(sum(b << (7 - i) for i, b in enumerate(bits[k:k + 8])) for k in range(0, len(bits), 8))


def huffman_table(w, entries):
    """spec 5.10.2: symbol_count, then (symbol, length) pairs as given; returns the
    canonical codes {symbol: (code, length)} of a valid table."""
    w.put(len(entries), 16)
    for symbol, length in entries:
        w.put(symbol, 16)
        w.put(length, 8)
    codes, code, last = {}, 0, None
    for symbol, length in entries:
        if last is not None and length < last:
            return {}  # not sorted: no canonical codes
        if last is not None:
            code = (code + 1) << (length - last)
        codes[symbol] = (code, length)
        last = length
    return codes
