"""A small range encoder and the PM integer codes, written from spec 5.6 and 6.5.

It lets mesh_vectors.py hand-build vertex-split records that the reference
encoder can never write (a split vertex beyond the batch, ring positions that are
not a valid split), so that the invalid vectors do not depend on the encoder's
own code. Only what those records need is here: adaptive bits, direct bits and
the unsigned and signed integer codes with their model sets.
"""

PROBABILITY_BITS = 11
PROBABILITY_ONE = 1 << PROBABILITY_BITS
ADAPT_SHIFT = 5


class IntegerModels:
    """An integer model set of spec 6.5.1: length[32], first_low_bit[32], sign."""

    def __init__(self):
        self.length = [PROBABILITY_ONE // 2] * 32
        self.first_low_bit = [PROBABILITY_ONE // 2] * 32
        self.sign = [PROBABILITY_ONE // 2]


class RangeEncoder:
    """Encodes what spec 5.6's decode_bit() and decode_direct() read back."""

    def __init__(self):
        self.out = bytearray()
        self.low = 0
        self.range = 0xFFFFFFFF
        self.cache = 0
        self.cache_size = 1

    def bit(self, models, index, bit):
        p0 = models[index]
        bound = (self.range >> PROBABILITY_BITS) * p0
        if bit == 0:
            self.range = bound
            models[index] = p0 + ((PROBABILITY_ONE - p0) >> ADAPT_SHIFT)
        else:
            self.low += bound
            self.range -= bound
            models[index] = p0 - (p0 >> ADAPT_SHIFT)
        self._normalize()

    def direct(self, value, n):
        for i in reversed(range(n)):
            self.range >>= 1
            if (value >> i) & 1:
                self.low += self.range
            self._normalize()

    def unsigned(self, m, value):
        """spec 6.5.1: the bit length of value + 1 in adaptive unary, then its low bits."""
        v1 = value + 1
        n = v1.bit_length() - 1
        for j in range(n):
            self.bit(m.length, j, 1)
        self.bit(m.length, n, 0)
        if n > 0:
            self.bit(m.first_low_bit, n, (v1 >> (n - 1)) & 1)
            self.direct(v1 & ((1 << (n - 1)) - 1), n - 1)

    def signed(self, m, value):
        self.unsigned(m, abs(value))
        if value != 0:
            self.bit(m.sign, 0, 1 if value < 0 else 0)

    def finish(self):
        """The coded string: it starts with the 0 byte spec 5.6 requires."""
        for _ in range(5):
            self._shift_low()
        return bytes(self.out)

    def _normalize(self):
        while self.range < (1 << 24):
            self.range = (self.range << 8) & 0xFFFFFFFF
            self._shift_low()

    def _shift_low(self):
        # The top byte of low goes out, 0xFF bytes wait until a carry is settled.
        if self.low < 0xFF000000 or self.low >= (1 << 32):
            carry = self.low >> 32
            temp = self.cache
            while True:
                self.out.append((temp + carry) & 0xFF)
                temp = 0xFF
                self.cache_size -= 1
                if self.cache_size == 0:
                    break
            self.cache = (self.low >> 24) & 0xFF
        self.cache_size += 1
        self.low = (self.low & 0x00FFFFFF) << 8


def zigzag(v):
    return 2 * v if v >= 0 else -2 * v - 1
