"""mrsv.StreamDecoder: bytes in pieces give what mrsv.decode gives."""
import numpy as np
import pytest

import mrsv


def pieces(data, size):
    return [data[i:i + size] for i in range(0, len(data), size)]


@pytest.fixture
def progressive(st_helens, tmp_path):
    path = tmp_path / "p.mrsv"
    mrsv.encode(st_helens, path, psnr=60, progressive=True)
    return path


@pytest.mark.parametrize("size", [1, 7, 1460, 1 << 20])
def test_pieces_give_the_one_shot_samples_and_levels(progressive, size):
    data = progressive.read_bytes()
    d = mrsv.StreamDecoder()
    levels = {}
    for piece in pieces(data, size):
        for unit in d.feed(piece):
            r = unit["complete_level"]
            if r >= 1 and r not in levels:  # coarse to fine, each once
                levels[r] = d.level(r)
    assert d.content == "grid" and d.problem is None and d.bytes_fed == len(data)
    d.finish()
    full, _ = mrsv.decode(progressive)
    assert np.array_equal(d.samples(), full)
    assert sorted(levels) == [1, 2, 3, 4]
    for r, samples in levels.items():
        assert np.array_equal(samples, mrsv.decode(progressive, levels=r)[0])


def test_errors_are_the_one_shot_errors(progressive):
    data = bytearray(progressive.read_bytes())
    data[-1] ^= 1  # MEND's CRC
    d = mrsv.StreamDecoder()
    with pytest.raises(mrsv.Error) as streamed:
        for piece in pieces(bytes(data), 100):
            d.feed(piece)
        d.finish()
    with pytest.raises(mrsv.Error) as one_shot:
        mrsv.decode(bytes(data))
    assert str(streamed.value) == str(one_shot.value)
    assert "E113" in str(streamed.value)


def test_a_prefix_finishes_as_the_prefix_decodes(progressive):
    data = progressive.read_bytes()
    d = mrsv.StreamDecoder()
    d.feed(data[:700])
    with pytest.raises(mrsv.Error) as streamed:
        d.finish()
    with pytest.raises(mrsv.Error) as one_shot:
        mrsv.decode(data[:700])
    assert str(streamed.value) == str(one_shot.value)
