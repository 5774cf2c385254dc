"""mrsv.check and mrsv.Error: valid and damaged streams."""
import numpy as np
import pytest

import mrsv

SIGNATURE = bytes([0x8E]) + b"MRSV\r\n\x1a\n"


@pytest.fixture
def stream(st_helens, tmp_path):
    path = tmp_path / "t.mrsv"
    mrsv.encode(st_helens, path, max_error=2, spacing=(30, 30))
    return path


def chunks(data):
    """(offset, type, length) of each chunk after the 12-byte file header."""
    out, at = [], 12
    while at < len(data):
        length = int.from_bytes(data[at + 4 : at + 8], "little")
        out.append((at, data[at : at + 4].decode(), length))
        at += 12 + length
    return out


def test_valid_stream(stream):
    report = mrsv.check(stream)
    assert report["kind"] == "grid" and report["complete"]
    assert report["shape"] == (128, 128) and report["sample_type"] == "int16"
    assert report["recorded"]["error_bound"] == "2"
    assert stream.read_bytes().startswith(SIGNATURE)


def test_damaged_payload_is_a_checksum_mismatch(stream):
    data = bytearray(stream.read_bytes())
    offset, kind, length = [c for c in chunks(data) if c[1] == "GBND"][0]
    data[offset + 8 + length // 2] ^= 0x10
    with pytest.raises(mrsv.Error) as caught:
        mrsv.check(bytes(data))
    e = caught.value
    assert (e.code, e.name) == (113, "checksum_mismatch")
    crc_offset = offset + 8 + length  # the offset of the chunk_crc field
    assert e.offset == crc_offset and e.field == "GBND.chunk_crc" and e.rule
    assert str(e).startswith(f"offset {crc_offset}: E113 checksum_mismatch: GBND.chunk_crc: ")
    # The decoder reports the same rule; it never crashes.
    with pytest.raises(mrsv.Error) as again:
        mrsv.decode(bytes(data))
    assert (again.value.code, again.value.offset) == (113, crc_offset)


def test_bad_signature(stream):
    data = bytearray(stream.read_bytes())
    data[1] = ord("X")
    with pytest.raises(mrsv.Error) as caught:
        mrsv.check(bytes(data))
    assert caught.value.code == 102 and caught.value.offset == 0


def test_truncated_stream(stream):
    data = stream.read_bytes()
    with pytest.raises(mrsv.Error) as caught:
        mrsv.check(data[: len(data) - 7])
    assert caught.value.code in (110, 111) and caught.value.offset > 0


def test_every_single_byte_flip_is_caught_or_harmless(stream):
    # Decoders never crash: every byte of the file flipped in turn.
    data = stream.read_bytes()
    for i in range(0, len(data), max(1, len(data) // 300)):
        damaged = bytearray(data)
        damaged[i] ^= 0xFF
        try:
            mrsv.check(bytes(damaged))
        except mrsv.Error as e:
            assert e.code > 100 and 0 <= e.offset <= len(data)


def test_error_is_an_exception_with_docs():
    assert issubclass(mrsv.Error, Exception)
    assert "offset" in mrsv.Error.__doc__


def test_missing_file(tmp_path):
    with pytest.raises(FileNotFoundError):
        mrsv.check(tmp_path / "absent.mrsv")
