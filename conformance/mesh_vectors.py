"""Conformance vectors of progressive meshes (spec 6), for make_coded_vectors.py.

Valid vectors are written by the reference encoder from real meshes: the Viewpoint
cow (closed) from ../shared/data/surface, and a window of the Mt. St. Helens
terrain crop in demo/data turned into a mesh here (open, with boundary; also with
its heights as the per-vertex scalar). Prefixes of the streams give the expected
meshes at several levels. Their expected output is the reference decoder's
canonical mesh (spec 6.8). Invalid vectors are valid ones edited chunk by chunk,
each breaking one rule; the code and offset are derived here from the layout.
"""
import os
import struct

from pm_coder import PROBABILITY_ONE, IntegerModels, RangeEncoder, zigzag

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.join(HERE, "..", "..", "shared", "data", "surface")
CROPS = os.path.join(HERE, "..", "demo", "data")


def terrain_mesh_text(fmt, size=20, origin=(40, 50)):
    """A size x size window of the St Helens crop as OBJ text or ASCII PLY with a scalar."""
    data = open(os.path.join(CROPS, "mt_st_helens_128x128_int16le.raw"), "rb").read()
    heights = [[struct.unpack_from("<h", data, 2 * ((origin[1] + y) * 128 + origin[0] + x))[0]
                for x in range(size)] for y in range(size)]
    verts = [(x * 10.0, y * 10.0, float(heights[y][x])) for y in range(size) for x in range(size)]
    tris = []
    for y in range(size - 1):
        for x in range(size - 1):
            a, b, c, d = y * size + x, y * size + x + 1, (y + 1) * size + x, (y + 1) * size + x + 1
            tris += [(a, b, d), (a, d, c)]
    if fmt == "obj":
        lines = [f"v {x} {y} {z}" for x, y, z in verts] + [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in tris]
        return "\n".join(lines) + "\n"
    head = ["ply", "format ascii 1.0", f"element vertex {len(verts)}", "property float x", "property float y",
            "property float z", "property float height", f"element face {len(tris)}",
            "property list uchar int vertex_indices", "end_header"]
    body = [f"{x} {y} {z} {z}" for x, y, z in verts] + [f"3 {a} {b} {c}" for a, b, c in tris]
    return "\n".join(head + body) + "\n"


def rings(canonical):
    """[(neighbour count, on the boundary)] of every vertex of a canonical mesh (spec 6.8)."""
    line_end = canonical.index(b"\n")
    _, _, v, t, _, s = canonical[:line_end].split()
    at = line_end + 1 + int(v) * (4 if int(s) else 3) * 4
    tris = [struct.unpack_from("<3I", canonical, at + 12 * i) for i in range(int(t))]
    edges = {}
    for tri in tris:
        for k in range(3):
            a, b = tri[k], tri[(k + 1) % 3]
            edges[(min(a, b), max(a, b))] = edges.get((min(a, b), max(a, b)), 0) + 1
    count, boundary = [0] * int(v), [False] * int(v)
    for (a, b), n in edges.items():
        for w in (a, b):
            count[w] += 1
            boundary[w] = boundary[w] or n == 1
    return list(zip(count, boundary))


def first_record(*values):
    """The first PSPL payload's coded string. Every split model is fresh there (6.5.3) and
    each value below uses a different one, so each gets a new model: ("unsigned", v) or
    ("bit", v). ("flags", [(context, flag), ...]) are split flags (6.7.1), which share
    the models split_flag[16]."""
    rc = RangeEncoder()
    split_flag = [PROBABILITY_ONE // 2] * 16
    for kind, value in values:
        if kind == "bit":
            rc.bit([PROBABILITY_ONE // 2], 0, value)
        elif kind == "flags":
            for context, flag in value:
                rc.bit(split_flag, context, flag)
        else:
            rc.unsigned(IntegerModels(), value)
    return rc.finish()


def split_vertex_zero(base_rings):
    """The first record's split flags naming vertex 0 of the base mesh (6.7.1)."""
    return ("flags", [(min(base_rings[0][0], 15), 1)])


def levels_of(stream):
    """Vertex counts of three levels of a PM stream (spec 6.8): the base mesh, about half
    of the splits, and the whole stream (from PHDR's vertex_count and base_vertex_count)."""
    vertices, base = struct.unpack_from("<II", stream, 12 + 8 + 4)
    return (base, base + (vertices - base) // 2, vertices)


def build_mesh(g, parse_chunks, frame, offset_of, find):
    cow = os.path.join(SHARED, "cow_viewpoint_2903v_5804tri.obj")
    terrain_obj = os.path.join(g.tmp, "terrain.obj")
    terrain_ply = os.path.join(g.tmp, "terrain_scalar.ply")
    with open(terrain_obj, "w") as f:
        f.write(terrain_mesh_text("obj"))
    with open(terrain_ply, "w") as f:
        f.write(terrain_mesh_text("ply"))

    def encode(path, options):
        return g.encode_file(path, options)

    def prefixes(name, data, clause, what):
        """The stream cut after PBAS and after about half of its batches (no MEND)."""
        chunks = parse_chunks(data)[:-1]  # without MEND
        base = find(chunks, "PBAS")
        splits = [i for i, (t, _) in enumerate(chunks) if t == "PSPL"]
        g.valid(f"{name}_prefix_base", frame(chunks[:base + 1]), clause, f"{what}: prefix up to PBAS, the base mesh")
        if len(splits) >= 2:
            half = splits[len(splits) // 2]
            g.valid(f"{name}_prefix_half", frame(chunks[:half + 1]), clause,
                    f"{what}: prefix of {len(splits) // 2 + 1} of {len(splits)} batches",
                    levels=levels_of(data)[:1])

    cow_stream = encode(cow, ["--bits", "14", "--placement", "endpoint"])
    g.valid("mesh_cow", cow_stream, "6", "the Viewpoint cow (closed), 14-bit positions, quadric cost, vs stays",
            levels=levels_of(cow_stream))
    prefixes("mesh_cow", cow_stream, "6.1, 6.7", "the cow")
    def valid_levels(name, stream, clause, description):
        g.valid(name, stream, clause, description, levels=levels_of(stream))

    valid_levels("mesh_cow_free", encode(cow, ["--bits", "12", "--placement", "free", "--free-from", "1"]), "6.7.3",
                 "the cow with free placement: every split also moves vs, along its plane on the grid of move_detail 4")
    valid_levels("mesh_cow_free_exact",
                 encode(cow, ["--bits", "12", "--placement", "free", "--free-from", "1", "--move-detail", "0"]),
                 "6.7.3", "the cow with free placement and move_detail 0: every move to the quantisation step")
    valid_levels("mesh_cow_paper", encode(cow, ["--bits", "10", "--cost", "paper", "--placement", "endpoint"]), "6",
                 "the cow simplified with the paper's energies (50, 1, 5), 10-bit positions")
    terrain = encode(terrain_obj, ["--bits", "16"])
    g.valid("mesh_terrain", terrain, "6.6.2, 6.7.2", "a terrain window as a mesh: boundary splits of every kind",
            levels=levels_of(terrain))
    prefixes("mesh_terrain", terrain, "6.1, 6.7", "the terrain mesh")
    valid_levels("mesh_terrain_scalar", encode(terrain_ply, ["--bits", "16", "--scalar", "height", "--scalar-bits", "12"]),
                 "6.4, 6.7.3", "a terrain window with its heights as the per-vertex scalar")

    # Invalid: header fields (6.2).
    chunks = parse_chunks(cow_stream)
    hdr_at = offset_of(chunks, 0) + 8

    def with_header(edit):
        payload = bytearray(chunks[0][1])
        edit(payload)
        return [("PHDR", bytes(payload))] + chunks[1:]

    def put(payload, at, fmt, value):
        struct.pack_into(fmt, payload, at, value)

    g.invalid("mesh_bad_placement", with_header(lambda p: put(p, 0, "<B", 2)), 301, "bad_mesh_header",
              hdr_at + 0, "6.2", "placement 2 is not defined")
    g.invalid("mesh_position_bits_zero", with_header(lambda p: put(p, 1, "<B", 0)), 301, "bad_mesh_header",
              hdr_at + 1, "6.2", "position_bits 0")
    g.invalid("mesh_position_bits_31", with_header(lambda p: put(p, 1, "<B", 31)), 301, "bad_mesh_header",
              hdr_at + 1, "6.2, B.5", "position_bits above 30")
    g.invalid("mesh_reserved", with_header(lambda p: put(p, 20, "<I", 1)), 105, "reserved_nonzero",
              hdr_at + 20, "6.2", "the reserved u32 of PHDR is not 0")
    g.invalid("mesh_move_detail_endpoint", with_header(lambda p: put(p, 3, "<B", 4)), 301, "bad_mesh_header",
              hdr_at + 3, "6.2", "move_detail 4 with placement 0 (vs never moves)")
    g.invalid("mesh_move_detail_31", with_header(lambda p: (put(p, 0, "<B", 1), put(p, 3, "<B", 31))), 301,
              "bad_mesh_header", hdr_at + 3, "6.2", "move_detail above 30")
    g.invalid("mesh_too_many_vertices", with_header(lambda p: put(p, 4, "<I", (1 << 28) + 1)), 301,
              "bad_mesh_header", hdr_at + 4, "6.2, B.5", "vertex_count above 2^28")
    g.invalid("mesh_base_two_vertices", with_header(lambda p: put(p, 8, "<I", 2)), 301, "bad_mesh_header",
              hdr_at + 8, "6.2", "base_vertex_count 2")
    g.invalid("mesh_step_zero", with_header(lambda p: put(p, 48, "<d", 0.0)), 301, "bad_mesh_header",
              hdr_at + 48, "6.2", "position_step 0")
    g.invalid("mesh_scalar_fields_without_scalar", with_header(lambda p: put(p, 64, "<d", 1.0)), 301,
              "bad_mesh_header", hdr_at + 64, "6.2", "scalar_step set although scalar_bits is 0")
    g.invalid("mesh_header_length", [("PHDR", chunks[0][1] + b"\0")] + chunks[1:], 117, "bad_chunk_length",
              offset_of(chunks, 0) + 4, "6.2", "a 73-byte PHDR")

    # Invalid: chunk order and counts (6.1, 6.7).
    mend = len(chunks) - 1
    base = find(chunks, "PBAS")
    first_split = find(chunks, "PSPL")
    c = chunks[:base] + [chunks[first_split], chunks[base]] + chunks[first_split + 1:]
    g.invalid("mesh_split_before_base", c, 116, "chunk_order", offset_of(c, base), "6.1", "PSPL before PBAS")
    c = chunks[:base + 1] + [chunks[base]] + chunks[base + 1:]
    g.invalid("mesh_two_bases", c, 116, "chunk_order", offset_of(c, base + 1), "6.1", "a second PBAS")
    c = chunks[:mend - 1] + chunks[mend:]
    g.invalid("mesh_missing_batch", c, 304, "split_count_mismatch", offset_of(c, len(c) - 1), "6.1",
              "a complete stream without its last PSPL")
    c = chunks[:mend] + [chunks[mend - 1]] + chunks[mend:]
    g.invalid("mesh_extra_batch", c, 304, "split_count_mismatch", offset_of(c, mend), "6.1",
              "one PSPL more than batch_count")
    c = list(chunks)
    c[first_split] = ("PSPL", struct.pack("<I", 0) + chunks[first_split][1][4:])
    g.invalid("mesh_split_count_zero", c, 304, "split_count_mismatch", offset_of(c, first_split) + 8, "6.7",
              "a batch of 0 splits")
    c = list(chunks)
    c[first_split] = ("PSPL", struct.pack("<I", 1 << 30) + chunks[first_split][1][4:])
    g.invalid("mesh_split_count_too_large", c, 304, "split_count_mismatch", offset_of(c, first_split) + 8,
              "6.7", "a batch of more splits than the stream has left")
    last = mend - 1
    c = list(chunks)
    c[last] = ("PSPL", chunks[last][1][:-3])
    g.invalid("mesh_truncated_record", c, 206, "bad_entropy_payload", offset_of(c, last) + 12, "6.7.3",
              "the last batch's coded splits cut 3 bytes short: a truncated record")
    c = list(chunks)
    c[last] = ("PSPL", chunks[last][1] + b"\0\0")
    g.invalid("mesh_trailing_coded_bytes", c, 206, "bad_entropy_payload", offset_of(c, last) + 12, "6.7",
              "two bytes after the last coded split")
    # Invalid: hand-coded first records (6.7), which the encoder cannot write.
    base_vertices = struct.unpack_from("<I", chunks[0][1], 8)[0]
    cow_rings = rings(g.reference_output(frame(chunks[:base + 1])))
    d, on_boundary = cow_rings[0]
    assert not on_boundary, "the cow is closed"

    def with_first_batch(coded):
        c = list(chunks)
        c[first_split] = ("PSPL", chunks[first_split][1][:4] + coded)
        return c

    record_at = offset_of(chunks, first_split) + 12
    assert len(cow_rings) == base_vertices
    no_split = ("flags", [(min(n, 15), 0) for n, _ in cow_rings])
    g.invalid("mesh_split_vertex_beyond_batch",
              with_first_batch(first_record(no_split)), 303,
              "bad_vertex_split", record_at, "6.7.1",
              f"the split flags of all {base_vertices} vertices of the batch's mesh are 0: no split vertex")
    g.invalid("mesh_split_not_a_neighbour",  # vs = 0, arc_start
              with_first_batch(first_record(split_vertex_zero(cow_rings), ("unsigned", 1024))),
              303, "bad_vertex_split", record_at, "6.7.2",
              f"vl named 1024 places back in a ring of {d}: a vertex that is not a neighbour of vs")
    g.invalid("mesh_split_same_neighbour",  # vs = 0, arc_start, turn
              with_first_batch(first_record(split_vertex_zero(cow_rings), ("unsigned", 0),
                                            ("unsigned", zigzag(-(d // 2))))),
              303, "bad_vertex_split", record_at, "6.7.2",
              "turn 0: vl and vr the same neighbour, a split that would make a non-manifold edge")

    terrain_chunks = parse_chunks(terrain)
    terrain_base = find(terrain_chunks, "PBAS")
    terrain_split = find(terrain_chunks, "PSPL")
    terrain_rings = rings(g.reference_output(frame(terrain_chunks[:terrain_base + 1])))
    d, on_boundary = terrain_rings[0]
    if on_boundary:
        # vs = 0, on_edge 1, last 0 (G2 only: (a, b) = (0, f)), then f = d, but a fan of d
        # neighbours has d - 1 faces.
        fan_too_wide = first_record(split_vertex_zero(terrain_rings), ("bit", 1), ("bit", 0), ("unsigned", d))
        c = list(terrain_chunks)
        c[terrain_split] = ("PSPL", terrain_chunks[terrain_split][1][:4] + fan_too_wide)
        g.invalid("mesh_split_fan_too_wide", c, 303, "bad_vertex_split", offset_of(c, terrain_split) + 12,
                  "6.7.2", f"a boundary split giving vt {d} faces of a fan that has {d - 1}")

    c = list(chunks)
    c[base] = ("PBAS", b"\x01" + chunks[base][1][1:])
    g.invalid("mesh_base_first_byte", c, 206, "bad_entropy_payload", offset_of(c, base) + 8, "6.4",
              "coded base mesh that does not start with a 0 byte")
