"""Hand-built conformance vectors, for make_vectors.py: rules that no encoder writes.

Every stream here is written from the text by this directory's own coders
(pm_coder.py, pm_writer.py, array_coder.py), never by the reference encoder, and
every expected output is computed from what was put in. Each vector exercises the
rules named for it in vector_rules.py.
"""
import struct

from array_coder import BitWriter, encode_line, huffman_table, weighted_long_prefix
from pm_coder import IntegerModels, RangeEncoder
from pm_writer import (Mesh, Models, Splitter, arc_normal, encode_base, first_use_order, header, plane_axis,
                       plane_offset)


def build_hand(v, H, chunk, ghdr, meta, canonical, MEND):
    grid_vectors(v, H, chunk, ghdr, meta, canonical, MEND)
    mesh_vectors(v, H, chunk, MEND)


# --- grids ------------------------------------------------------------------

def whdr(order=1, levels=(0, 0, 0), entropy_mode=1, frac_bits=0, flags=0, precinct_log2=0, offset=0, scale=0):
    """spec 5.2 wavelet_header(); `offset` and `scale` are the raw u64 fields."""
    return struct.pack("<B3BBBBBQQ", order, *levels, entropy_mode, frac_bits, flags, precinct_log2, offset, scale)


def gbnd(index, coded, step=1, flags=0, reserved=0):
    """spec 5.3 band()."""
    return struct.pack("<HBBQ", index, flags, reserved, step) + coded


def grid_vectors(v, H, chunk, ghdr, meta, canonical, MEND):
    at = 12  # the first chunk's offset

    def offsets(*payloads):
        """Offsets of the chunks after the file header."""
        out, p = [], at
        for payload in payloads:
            out.append(p)
            p += 12 + len(payload)
        return out

    # -- metadata (2.6) --
    one = chunk("GHDR", ghdr("uint8", [1]))
    graw = chunk("GRAW", b"\x2a")
    meta_at = at + len(one) + 8
    v.valid("meta_unknown_key", H + one + chunk("meta", meta([("vendor.note", "kept, not checked")])) + graw + MEND,
            canonical("uint8", [1], b"\x2a"), "2.6", "an entry with a key this text does not register")

    def meta_case(name, payload, rel, description):
        v.invalid(name, H + one + chunk("meta", payload) + graw + MEND, 130, "bad_metadata", meta_at + rel, "2.6",
                  description)

    meta_case("meta_key_too_long", b"a" * 65 + b"=1\n", 0, "a key of 65 bytes")
    meta_case("meta_control_char", b"units=m\ndescription=tab\there\n", 8, "a TAB in a value")
    entries = b"".join(b"k%d=1\n" % i for i in range(1025))
    meta_case("meta_too_many_entries", entries, entries.index(b"k1024="), "1,025 entries")
    meta_case("meta_too_large", b"description=" + b"x" * 65525 + b"\n", 0, "a payload of 65,538 bytes")
    v.invalid("stored_grid_with_whdr", H + one + chunk("WHDR", whdr()) + graw + MEND, 116, "chunk_order",
              at + len(one), "3.3", "a WHDR chunk in a stored grid (coding 0)")
    # Two rules broken: the order of 3.1's table decides (row 4 before row 5).
    v.invalid("ghdr_reserved_before_num_dims_order", H + chunk("GHDR", ghdr("uint8", [1], num_dims=0, flags=0x80)) + graw
              + MEND, 105, "reserved_nonzero", 23, "3.1, A.2",
              "grid_flags reserved bit and num_dims 0: the reserved bit is checked first")

    # -- wavelet headers (5.2, 4.3) --
    def wavelet(name, dims, stype, header_payload, rel, error, error_name, clause, description, nodata=None):
        g = chunk("GHDR", ghdr(stype, dims, coding=1, nodata_bits=nodata))
        w_at = at + len(g)
        v.invalid(name, H + g + chunk("WHDR", header_payload), error, error_name, w_at + rel, clause, description)

    wavelet("whdr_padded_too_large", [2048, 2048, 1024], "uint8", whdr(order=2, levels=(1, 0, 0)), 9, 204,
            "bad_wavelet_header", "5.2", "2^32 samples whose padded array (2049 x 2048 x 1024) exceeds 2^32 values")
    wavelet("whdr_spline_too_few_intervals", [61], "int32", whdr(order=4, levels=(3, 0, 0)), 9, 204,
            "bad_wavelet_header", "4.3, 5.2", "cubic B-splines, 3 levels on 61 samples: 8 coarse intervals, below 11")
    wavelet("whdr_no_plan_y", [64, 5], "int32", whdr(order=2, levels=(1, 1, 0)), 10, 204, "bad_wavelet_header",
            "5.2", "linear B-splines: x has a plan, y (5 samples, 1 level: 2 intervals, below 4) has none")
    wavelet("whdr_residual_float", [4], "float32", whdr(flags=2, scale=struct.unpack("<Q", struct.pack("<d", 1.0))[0]),
            14, 204, "bad_wavelet_header", "5.2", "has_residual with float32 samples")
    wavelet("whdr_precinct_3", [4], "int32", whdr(precinct_log2=3), 15, 204, "bad_wavelet_header", "5.2",
            "precinct_log2 3 (0, or 4 to 24)")
    wavelet("whdr_precinct_25", [4], "int32", whdr(precinct_log2=25), 15, 204, "bad_wavelet_header", "5.2",
            "precinct_log2 25 (0, or 4 to 24)")
    wavelet("whdr_order_before_precinct_order", [4], "int32", whdr(order=6, precinct_log2=1), 8, 204,
            "bad_wavelet_header", "5.2, A.2", "order 6 and precinct_log2 1: order is checked first")

    # -- a hand-coded 1-D int32 grid, levels 0: one band, the samples themselves --
    g4 = chunk("GHDR", ghdr("int32", [4], coding=1))
    w = chunk("WHDR", whdr())
    band_at = at + len(g4) + len(w)
    values = [(1 << 39) + 14, -((1 << 20) + 15), 7, 0]  # the first: escape n = 38, h = 1, all bits 1
    samples = [max(-(1 << 31), min((1 << 31) - 1, max(-(1 << 35) + 1, min((1 << 35) - 1, x)))) for x in values]
    v.valid("array_largest_escape", H + g4 + w + chunk("GBND", gbnd(0, encode_line(values))) + MEND,
            canonical("int32", [4], struct.pack("<4i", *samples)), "5.4, 5.7.3, 5.8.2",
            "the largest escape (prefix of 38 bits): 2^39 + 14, saturated to 2^35 - 1, clamped to int32")
    v.invalid("array_magnitude_prefix_39", H + g4 + w + chunk("GBND", gbnd(0, encode_line([20, 0, 0, 0], (0, 39))))
              + MEND, 206, "bad_entropy_payload", band_at + 20, "5.7.3", "an escape prefix of 39 one bits")
    v.invalid("weighted_magnitude_prefix_39", H + g4 + w + chunk("GBND", gbnd(0, weighted_long_prefix(), flags=2))
              + MEND, 206, "bad_entropy_payload", band_at + 20, "5.7.5",
              "weighted prediction: a magnitude prefix of 39 one bits")
    v.invalid("band_reserved_before_step_order", H + g4 + w + chunk("GBND", gbnd(0, b"", step=1 << 35, reserved=1)) + MEND,
              105, "reserved_nonzero", band_at + 11, "5.3, A.2", "reserved byte and step 2^35: reserved first")
    v.invalid("pbas_in_wavelet_grid", H + g4 + w + chunk("PBAS", b"\0" * 5) + chunk("GBND", gbnd(0, encode_line([1, 2, 3, 4])))
              + MEND, 116, "chunk_order", band_at, "5.1", "a PBAS chunk after WHDR in a wavelet-coded grid")
    one_band = chunk("GBND", gbnd(0, encode_line([1, 2, 3, 4])))
    v.invalid("band_beyond_plan", H + g4 + w + one_band + chunk("GBND", gbnd(1, encode_line([1, 2, 3, 4]))) + MEND,
              116, "chunk_order", band_at + len(one_band), "5.1", "a second GBND for a plan of one band")
    v.invalid("wavelet_no_whdr_at_mend", H + g4 + MEND, 116, "chunk_order", at + len(g4), "5.1",
              "a complete wavelet-coded grid without WHDR")

    # -- mask and residual (5.1, 5.5) --
    gm = chunk("GHDR", ghdr("int32", [4], coding=1, nodata_bits=0x80000000))
    mask_flags = chunk("WHDR", whdr(flags=3))
    band = chunk("GBND", gbnd(0, encode_line([5, 6, 0, 8])))
    mask = chunk("GMSK", encode_line([0, 0, 1, 0]))
    res = chunk("GRES", struct.pack("<I", 3) + encode_line([1, -1, None, 0]))
    m_at = at + len(gm) + len(mask_flags)
    full = [gm, mask_flags, mask, band, res]
    expected = struct.pack("<4i", 5 + 3, 6 - 3, -(1 << 31), 8)
    v.valid("mask_residual_hand", H + b"".join(full) + MEND, canonical("int32", [4], expected, nodata_bits=0x80000000),
            "5.5, 5.8.2", "a hand-coded mask and residual (the masked position skipped by the residual)")
    v.invalid("gmsk_without_has_mask", H + gm + chunk("WHDR", whdr(flags=2)) + mask + band + res + MEND, 116,
              "chunk_order", m_at, "5.1", "GMSK while has_mask is clear")
    v.invalid("gmsk_twice", H + gm + mask_flags + mask + mask + band + res + MEND, 116, "chunk_order",
              m_at + len(mask), "5.1", "a second GMSK")
    v.invalid("gmsk_value_2", H + gm + mask_flags + chunk("GMSK", encode_line([0, 2, 1, 0])) + band + res + MEND, 206,
              "bad_entropy_payload", m_at + 8, "5.5", "a mask value of 2")
    v.invalid("gmsk_first_byte", H + gm + mask_flags + chunk("GMSK", b"\x01" + encode_line([0, 0, 1, 0])[1:]) + band
              + res + MEND, 206, "bad_entropy_payload", m_at + 8, "5.5", "a mask string that does not start with 0")
    r_at = m_at + len(mask) + len(band)
    v.invalid("gres_without_has_residual", H + gm + chunk("WHDR", whdr(flags=1)) + mask + band + res + MEND, 116,
              "chunk_order", r_at, "5.1", "GRES while has_residual is clear")
    v.invalid("gres_twice", H + gm + mask_flags + mask + band + res + res + MEND, 116, "chunk_order", r_at + len(res),
              "5.1", "a second GRES")
    v.invalid("gres_short", H + gm + mask_flags + mask + band + chunk("GRES", b"\x03\0\0") + MEND, 117,
              "bad_chunk_length", r_at + 4, "5.5", "a GRES payload of 3 bytes")
    v.invalid("gres_first_byte", H + gm + mask_flags + mask + band + chunk("GRES", struct.pack("<I", 3) + b"\x01"
              + encode_line([1, -1, None, 0])[1:]) + MEND, 206, "bad_entropy_payload", r_at + 12, "5.5",
              "a residual string that does not start with 0")

    # -- the baseline mode (5.10): the same 1-D grid, entropy_mode 0 --
    wb = chunk("WHDR", whdr(entropy_mode=0))
    b_at = at + len(g4) + len(wb)

    def baseline(table, bits, pad=0, extra=b"", cut=0):
        w2 = BitWriter()
        codes = huffman_table(w2, table)
        for kind, value, n in bits:
            if kind == "code":
                code, length = codes[value]
                w2.put(code, length)
            else:
                w2.put(value, n)
        data = w2.bytes(pad) + extra
        return data[:len(data) - cut] if cut else data

    good_table = [(0, 1), (3, 2), (2 * 64 + 3, 2)]
    good_bits = [("code", 2 * 64 + 3, 0), ("bits", 0b001, 3), ("code", 0, 0)]  # [0, 0, 5, 0]
    v.valid("baseline_hand", H + g4 + wb + chunk("GBND", gbnd(0, baseline(good_table, good_bits))) + MEND,
            canonical("int32", [4], struct.pack("<4i", 0, 0, 5, 0)), "5.10",
            "a hand-coded baseline array: a run of 2, then 5, then the end symbol")

    def base_case(name, payload, description):
        v.invalid(name, H + g4 + wb + chunk("GBND", gbnd(0, payload)) + MEND, 206, "bad_entropy_payload", b_at + 20,
                  "5.10", description)

    base_case("baseline_past_end", baseline(good_table, []), "a table and no symbols: reading past the end")
    base_case("baseline_size0_symbol", baseline([(0, 1), (64, 2), (131, 2)], good_bits[:1]),
              "the table lists run 1, size 0: not a run/size symbol")
    base_case("baseline_run_past_end", baseline([(0, 1), (4 * 64 + 1, 1)], [("code", 257, 0), ("bits", 0, 1)]),
              "a run of 4 zeros in an array of 4")
    base_case("baseline_no_symbols", baseline([], []) + b"\0", "symbol_count 0")
    base_case("baseline_unsorted", baseline([(3, 2), (0, 1), (131, 2)], []), "the table is not sorted by length")
    base_case("baseline_kraft", baseline([(0, 1), (3, 1), (131, 1)], []), "three codes of length 1")
    base_case("baseline_no_code", baseline([(0, 1)], [("bits", (1 << 20) - 1, 20)]), "20 bits that match no code")
    base_case("baseline_padding", baseline(good_table, good_bits, pad=1), "the bits after the last symbol are 1")
    base_case("baseline_extra_byte", baseline(good_table, good_bits, extra=b"\0"), "a byte after the array")
    base_case("baseline_length_21", baseline([(0, 21)], []), "a code length of 21")


# --- progressive meshes -----------------------------------------------------

OCTAHEDRON = [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]
TETRAHEDRON = [[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]]


def octahedron(bits):
    """A closed octahedron with uneven arms, numbered by first use, at `bits`-bit positions."""
    c = 1 << (bits - 1)
    r = [c // 2 + 12345, c // 2 - 777, c // 3 + 4321, c // 2 + 99, c // 3 - 55, c // 2 + 3]
    p = [[c + r[0], c + 11, c - 7], [c - r[1], c + 5, c + 13], [c + 17, c + r[2], c - 3],
         [c - 9, c - r[3], c + 2], [c + 6, c - 4, c + r[4]], [c - 1, c + 8, c - r[5]]]
    return first_use_order(p, OCTAHEDRON)


def mesh_stream(H, chunk, MEND, hdr, chunks, complete=True):
    return H + chunk("PHDR", hdr) + b"".join(chunk(t, p) for t, p in chunks) + (MEND if complete else b"")


def mesh_vectors(v, H, chunk, MEND):
    at = 12
    bits = 24

    # -- a valid stream with position_bits 24: the arc normal's shift and halving (6.7.3) --
    base = octahedron(bits)
    models = Models()
    pbas = encode_base(models, base)
    s = Splitter(models, base, bits)
    s.begin_batch()
    seen = [s.split(0, 1, 3, _telling_vt(base, 0, 1, 3, bits))]
    first = s.end_batch(1)
    s.begin_batch()
    p = s.mesh.positions
    second_vs = min(w for w in range(2, len(p)) if w not in s.mesh.neighbours(1))
    seen.append(s.split(1, 0, 2, [p[1][0] - 200001, p[1][1] + 150003, p[1][2] + 99999]))
    seen.append(s.split(second_vs, 2, 0, [p[second_vs][0] + 7, p[second_vs][1] - 250000, p[second_vs][2] + 180001]))
    second = s.end_batch(2)
    # The vector must tell a decoder without the shift, or without the halving, from a
    # right one: some prediction of vt must differ (and the halving must run at all).
    for shift, halve in ((False, True), (True, False)):
        assert any(_prediction(info, bits, shift, halve) != info["predicted"] for info in seen), (shift, halve)
    hdr = header(len(s.mesh.positions), base, 2, bits)
    stream = [("PBAS", pbas), ("PSPL", first), ("PSPL", second)]
    levels = [(len(m.positions), m.canonical(bits, 0)) for m in s.levels]
    v.valid("mesh_hand_24_bits", mesh_stream(H, chunk, MEND, hdr, stream), levels[-1][1], "6.7.3",
            "an octahedron at 24-bit positions, three splits in two batches: arc normals from differences "
            "shifted by 4 bits and halved below 2^30", levels=levels)
    v.valid("mesh_hand_prefix_header", mesh_stream(H, chunk, MEND, hdr, [], complete=False),
            b"mrsv-canonical-mesh 1 0 0 %d 0\n" % bits, "6.1, 6.8", "a prefix of PHDR alone: the empty level")
    v.valid("mesh_hand_prefix_one_batch", mesh_stream(H, chunk, MEND, hdr, stream[:2], complete=False),
            levels[1][1], "6.1, 6.8", "a prefix of the base mesh and the first batch", levels=levels[:2])

    hdr_at = at + 8
    pbas_at = at + 12 + 72
    pspl_at = pbas_at + 12 + len(pbas)

    def with_header(name, edit, error, error_name, rel, clause, description):
        h = bytearray(hdr)
        edit(h)
        v.invalid(name, mesh_stream(H, chunk, MEND, bytes(h), stream), error, error_name, hdr_at + rel, clause,
                  description)

    put = struct.pack_into
    with_header("phdr_scalar_bits_31", lambda h: put("<B", h, 2, 31), 301, "bad_mesh_header", 2, "6.2",
                "scalar_bits 31")
    with_header("phdr_base_triangles_zero", lambda h: put("<I", h, 12, 0), 301, "bad_mesh_header", 12, "6.2",
                "base_triangle_count 0")
    with_header("phdr_batch_count_above_splits", lambda h: put("<I", h, 16, 4), 301, "bad_mesh_header", 16, "6.2",
                "4 batches for 3 splits")
    with_header("phdr_batch_count_zero", lambda h: put("<I", h, 16, 0), 301, "bad_mesh_header", 16, "6.2",
                "batch_count 0 with 3 splits")
    with_header("phdr_origin_nan", lambda h: put("<d", h, 32, float("nan")), 301, "bad_mesh_header", 32, "6.2",
                "origin y is a NaN")
    with_header("phdr_scalar_origin_without_scalar", lambda h: put("<d", h, 56, -0.0), 301, "bad_mesh_header", 56,
                "6.2", "scalar_origin -0 although scalar_bits is 0")
    with_header("phdr_reserved_before_step_order", lambda h: (put("<I", h, 20, 1), put("<d", h, 48, 0.0)), 105,
                "reserved_nonzero", 20, "6.2, A.2", "the reserved u32 and position_step 0: reserved first")

    # -- chunk order (6.1) and PSPL framing (6.7) --
    def streamed(name, chunks, error, error_name, offset, clause, description, complete=True):
        v.invalid(name, mesh_stream(H, chunk, MEND, hdr, chunks, complete), error, error_name, offset, clause,
                  description)

    streamed("pm_grid_chunk", [stream[0], ("WHDR", whdr())] + stream[1:], 116, "chunk_order", pspl_at, "6.1",
             "a WHDR chunk in a PM stream")
    streamed("pm_no_pbas_at_mend", [], 116, "chunk_order", pbas_at, "6.1", "a complete PM stream without PBAS")
    streamed("pspl_short", [stream[0], ("PSPL", b"\x01\0\0")] + stream[2:], 117, "bad_chunk_length", pspl_at + 4,
             "6.7", "a PSPL payload of 3 bytes")
    streamed("pspl_first_byte", [stream[0], ("PSPL", first[:4] + b"\x01" + first[5:])] + stream[2:], 206,
             "bad_entropy_payload", pspl_at + 12, "6.7", "coded splits that do not start with 0")
    streamed("pspl_empty_string", [stream[0], ("PSPL", first[:4])] + stream[2:], 206, "bad_entropy_payload",
             pspl_at + 12, "6.7", "a PSPL with split_count and no coded string")
    meta_payload = b"Bad=1\n"
    v.invalid("pm_meta_bad_key", H + chunk("PHDR", hdr) + chunk("meta", meta_payload) +
              b"".join(chunk(t, p) for t, p in stream) + MEND, 130, "bad_metadata", pbas_at + 8, "2.6",
              "a meta entry with an upper-case key in a PM stream")

    # -- base meshes (6.4, 6.5.1): a tetrahedron --
    tet = first_use_order([[10, 10, 10], [200, 10, 10], [10, 200, 10], [10, 10, 200]], TETRAHEDRON)

    def base_stream(name, payload, error, description, tris=4, verts=4, clause="6.4"):
        h = bytearray(header(verts, tet, 0, 8))
        put("<II", h, 8, verts, tris)
        v.invalid(name, mesh_stream(H, chunk, MEND, bytes(h), [("PBAS", payload)]), error,
                  {302: "bad_base_mesh", 206: "bad_entropy_payload"}[error], pbas_at + 8, clause, description)

    good = encode_base(Models(), tet)
    v.valid("mesh_hand_tetrahedron", mesh_stream(H, chunk, MEND, header(4, tet, 0, 8), [("PBAS", good)]),
            tet.canonical(8, 0), "6.4", "a tetrahedron as a base mesh and nothing else")
    rc = RangeEncoder()
    rc.signed(IntegerModels(), -1)
    base_stream("pbas_vertex_outside", rc.finish(), 302, "the first base vertex at x = -1")
    base_stream("pbas_too_many_new", _too_many_new(tet), 302, "a fifth new vertex among 4 base vertices")
    base_stream("pbas_back_reference_ahead", _back_ahead(tet), 302, "a back reference to a vertex not yet introduced")
    base_stream("pbas_unused_vertex", encode_base(Models(), Mesh(tet.positions + [[5, 5, 5]], tet.triangles)), 302,
                "5 base vertices, 4 used", verts=5)
    base_stream("pbas_truncated", good[:-2], 206, "the base string two bytes short")
    base_stream("pbas_trailing", good + b"\0", 206, "a byte after the base string")
    base_stream("pbas_repeated_corner", encode_base(Models(), Mesh(tet.positions, tet.triangles + [[0, 1, 1]])), 302,
                "a triangle (0, 1, 1)", tris=5)
    base_stream("pbas_edge_three_triangles", encode_base(Models(), Mesh(tet.positions, tet.triangles + [[0, 1, 3]])),
                302, "a fifth triangle on edge (0, 1): three triangles", tris=5)
    flipped = [list(t) for t in tet.triangles]
    flipped[3] = [flipped[3][0], flipped[3][2], flipped[3][1]]
    base_stream("pbas_orientation", encode_base(Models(), Mesh(tet.positions, flipped)), 302,
                "one triangle of the tetrahedron turned over")
    bow = [[0, 1, 2], [0, 3, 4]]  # two triangles sharing vertex 0 only: two fans
    base_stream("pbas_two_fans", encode_base(Models(), Mesh([[1, 1, 1], [9, 1, 1], [1, 9, 1], [1, 1, 9], [9, 9, 9]], bow)),
                302, "two triangles that share one vertex: two fans at it", tris=2, verts=5)
    rc = RangeEncoder()
    m = IntegerModels()
    for j in range(31):
        rc.bit(m.length, j, 1)
    base_stream("pbas_length_prefix_31", rc.finish(), 302, "a length prefix of 31 one bits", clause="6.5.1")
    rc = RangeEncoder()
    rc.unsigned(IntegerModels(), 1 << 30)
    base_stream("pbas_magnitude_2_30", rc.finish(), 302, "a position difference of 2^30", clause="6.5.1")

    # -- vertex splits (6.7) --
    def first_batch(models_after_base, mesh, write, splits=1):
        """A PSPL payload whose records `write(splitter)` codes after the flags."""
        sp = Splitter(models_after_base, mesh, bits)
        sp.begin_batch()
        write(sp)
        return sp.end_batch(splits)

    def split_case(name, write, description, clause="6.7", placement=0, move_detail=0, mesh=None, extra=None):
        mesh = mesh or base
        ms = Models()
        b = encode_base(ms, mesh)
        h = header(len(mesh.positions) + 1, mesh, 1, bits, placement=placement, move_detail=move_detail)
        payload = first_batch(ms, mesh, write)
        chunks = [("PBAS", b), ("PSPL", payload)]
        offset = at + 12 + 72 + 12 + len(b) + 12
        v.invalid(name, mesh_stream(H, chunk, MEND, h, chunks), 303, "bad_vertex_split", offset, clause, description)

    def arc_start_prefix(sp):
        sp.flags(0)
        ring, _ = sp.mesh.ring(0)
        m = sp.models.arc_start[min(len(ring), 15)]
        for j in range(31):
            sp.rc.bit(m.length, j, 1)

    split_case("split_length_prefix_31", arc_start_prefix, "the arc start's length prefix of 31 one bits",
               clause="6.5.1")

    def move(units, fine=None):
        def write(sp):
            sp.flags(0)
            ring, _ = sp.mesh.ring(0)
            d = len(ring)
            sp.rc.unsigned(sp.models.arc_start[min(d, 15)], 0)
            sp.rc.unsigned(sp.models.turn[min(d, 15)], 0)
            if fine is not None:
                sp.rc.bit(sp.models.move_fine, 0, fine)
            for t, u in enumerate(units):
                sp.rc.signed(sp.models.vs_move[t], u)
        return write

    # Ring edges of about 2^22 give L of about 2^45: g = 22 - move_detail 1 = 21.
    split_case("split_move_limit", move([(1 << 29) - 1], fine=0), "a tangential move of (2^29 - 1) x 2^21, "
               "far beyond 2^30: a decoder that computes on with it overflows", clause="6.7.3", placement=1,
               move_detail=1)
    split_case("split_vs_outside", move([-(1 << 24) + 1, 0, 0]), "a move that takes vs below 0", clause="6.7.3",
               placement=1)

    def vt_outside(sp):
        sp.split(0, 0, 2, list(sp.mesh.positions[0]),
                 residual_hook=lambda kind, value: -(1 << 24) if kind == "tangent" else value)

    split_case("split_vt_outside", vt_outside, "vt's first tangential coordinate below 0", clause="6.7.3")

    def ring_cone(sp):
        sp.flags(0)

    n = 1025
    cone_pos = [[500, 500, 900], [500, 500, 100]] + [[500 + (i * 37) % 300, 500 + (i * 91) % 300, 500]
                                                     for i in range(n)]
    cone = []
    for i in range(n):
        r0, r1 = 2 + i, 2 + (i + 1) % n
        cone += [[0, r0, r1], [1, r1, r0]]
    cone_mesh = first_use_order(cone_pos, cone)
    split_case("split_ring_above_1024", ring_cone, "a split vertex with 1,025 neighbours", clause="6.7.1",
               mesh=cone_mesh)

    lone = first_use_order([[1, 1, 1], [9, 1, 1], [1, 9, 1]], [[0, 1, 2]])

    def fan_interior(sp):
        sp.flags(0)
        sp.rc.bit(sp.models.boundary_kind, 0, 0)  # on_edge 0; a = truncated(1) reads nothing
        sp.rc.unsigned(sp.models.fan_interior, 1)

    split_case("split_fan_interior_beyond", fan_interior, "a boundary split with b = a + 2 in a fan of one face",
               clause="6.7.2", mesh=lone)

    # A scalar outside [0, 2^scalar_bits).
    ms = Models()
    sbase = Mesh(base.positions, base.triangles, [10, 20, 30, 40, 50, 60])
    sb = encode_base(ms, sbase, scalar_bits=8)
    sp = Splitter(ms, sbase, bits, scalar_bits=8)
    sp.begin_batch()
    sp.split(0, 0, 2, list(sbase.positions[0]), vt_scalar=300)
    payload = sp.end_batch(1)
    h = header(7, sbase, 1, bits, scalar_bits=8, scalar_step=1.0)
    v.invalid("split_scalar_outside", mesh_stream(H, chunk, MEND, h, [("PBAS", sb), ("PSPL", payload)]), 303,
              "bad_vertex_split", at + 12 + 72 + 12 + len(sb) + 12, "6.7.3", "vt's scalar 300 with scalar_bits 8")


def _telling_vt(mesh, vs, a, b, bits):
    """A place for vt whose predicted plane coordinate differs when the arc normal's shift
    or its halving is left out (the first found, in a fixed order)."""
    p = mesh.positions[vs]
    for i in range(1, 5000):
        vt = [p[0] + 1000 + 7919 * i, p[1] + 400000 - 104729 * i % 1000003, p[2] - 300000 + 31 * i]
        trial = Splitter(Models(), mesh, bits)
        trial.begin_batch()
        info = trial.split(vs, a, b, vt)
        if all(_prediction(info, bits, shift, halve) != info["predicted"]
               for shift, halve in ((False, True), (True, False))):
            return vt
    raise AssertionError("no place for vt tells the arc normal's shift and halving")


def _prediction(info, bits, shift, halve):
    """vt's predicted coordinate on the plane axis as a decoder with the arc normal's shift
    or halving left out would compute it (or None when its plane axis differs)."""
    pos, vs, a, c = info["positions"], info["vs"], info["a"], info["c"]
    n = arc_normal(pos, pos[vs], info["ring"], a, c - 2, bits, shift, halve)
    if plane_axis(n) != info["axis"]:
        return None
    axis = info["axis"]
    offsets = [info["vt"][x] - pos[vs][x] for x in range(3)]
    return min(max(pos[vs][axis] + plane_offset(n, axis, offsets), 0), (1 << bits) - 1)


def _too_many_new(tet):
    """Corners that introduce a fifth vertex among four (6.4)."""
    rc, ms = RangeEncoder(), Models()
    last = [0, 0, 0]
    for p in tet.positions:
        for a in range(3):
            rc.signed(ms.base_position[a], p[a] - last[a])
        last = p
    for j in range(3):
        rc.bit(ms.base_new_vertex, j, 1)
    rc.bit(ms.base_new_vertex, 0, 1)
    rc.bit(ms.base_new_vertex, 1, 1)  # the fifth
    return rc.finish()


def _back_ahead(tet):
    """A first corner that refers back to a vertex before any is introduced (6.4)."""
    rc, ms = RangeEncoder(), Models()
    last = [0, 0, 0]
    for p in tet.positions:
        for a in range(3):
            rc.signed(ms.base_position[a], p[a] - last[a])
        last = p
    rc.bit(ms.base_new_vertex, 0, 0)
    rc.unsigned(ms.base_back_reference, 0)
    return rc.finish()
