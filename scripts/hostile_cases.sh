#!/usr/bin/env bash
# The hostile cases of issue 26, made and run one at a time: prints one Markdown table row
# per case (exit status, wall and CPU time, peak memory, first non-empty line of stderr, a
# note).
#
#   scripts/hostile_cases.sh BIN_RENDER BIN_MERGE OUTDIR
#
# Every case runs under `/usr/bin/time -v`, `timeout --foreground -k 5 60` and an address-space limit of
# 6 GiB (`ulimit -v 6291456`). The large inputs are generated in OUTDIR (sparse files through
# `truncate`, OBJ/PLY/PNG/EXR written by the Python helper below); nothing of them is kept
# in the repository. Signals are sent with `kill` once the phase they test has begun:
# loading (before the header line is printed), rendering or the MLT bootstrap (after it).
# `--threads` cases run under `timeout -k 1 5`, whatever the binary: the programs from before
# the fix spawn threads until killed, so the thread count (`ps -o nlwp`) is sampled at 2 s
# (and the most threads seen, sampled every 0.2 s from /proc, is reported beside it).
# Results and the command lines are in docs/hostile-cases.md.
set -u

if [ $# -ne 3 ]; then
    echo "usage: $0 BIN_RENDER BIN_MERGE OUTDIR" >&2
    exit 2
fi
RENDER=$(realpath "$1")
MERGE=$(realpath "$2")
mkdir -p "$3"
OUT=$(realpath "$3")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
CORNELL=${CORNELL:-/work/shared/scenes/cornell-box.xml}
[ -f "$CORNELL" ] || CORNELL=$ROOT/mcrt-render/tests/data/cornell-box.xml
LIMIT=60  # TEXTURES_LIMIT overrides it for the six textures (slow to decode on a loaded machine)
AS_LIMIT_KB=6291456
# The programs after the fix hold the MLT bootstrap's 2³² − 1 samples against a memory
# budget; `--max-memory 1T` admits them so that the signal reaches the bootstrap.
BIG_BUDGET=()
if "$RENDER" --help 2>/dev/null | grep -q -- --max-memory; then BIG_BUDGET=(--max-memory 1T); fi

PY=$OUT/hostile_helper.py
cat >"$PY" <<'PYEOF'
"""Generators and readers for scripts/hostile_cases.sh (standard library; numpy and
mitsuba only for `brightest`)."""
import math, struct, sys, zlib


def png(path, w, h, value=100):
    """An 8-bit RGB PNG of one colour, written row by row."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    z = zlib.compressobj(9)
    row = b"\x00" + bytes([value]) * (3 * w)
    idat = b"".join(z.compress(row) for _ in range(h)) + z.flush()
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", idat) + chunk(b"IEND", b""))


def obj_soup(path, n, shared):
    """n copies of one triangle: on three shared vertices, or each on its own three
    (tests/it/common/degenerate.rs: identical, stacked)."""
    tri = ["v -0.5 -0.5 0", "v 0.5 -0.5 0", "v 0 0.5 0"]
    with open(path, "w") as f:
        if shared:
            f.write("\n".join(tri) + "\n")
            f.write("f 1 2 3\n" * n)
        else:
            f.write(("\n".join(tri) + "\n") * n)
            f.write("".join(f"f {3*i+1} {3*i+2} {3*i+3}\n" for i in range(n)))


def obj_shifted(path, n):
    """n copies of one triangle, copy i moved by i · 10⁻⁵ along x: coplanar and overlapping
    (tests/it/common/degenerate.rs: shifted)."""
    with open(path, "w") as f:
        for i in range(n):
            dx = i * 1e-5
            f.write(f"v {dx - 0.5:.6f} -0.5 0\nv {dx + 0.5:.6f} -0.5 0\nv {dx:.6f} 0.5 0\n")
        f.write("".join(f"f {3*i+1} {3*i+2} {3*i+3}\n" for i in range(n)))


def obj_grid(path, n):
    """An n × n grid of vertices in [0, 1]², (n − 1)² quads."""
    with open(path, "w") as f:
        for i in range(n):
            f.write("".join(f"v {i/n} {j/n} 0\n" for j in range(n)))
        for i in range(n - 1):
            f.write("".join(f"f {i*n+j+1} {i*n+j+2} {i*n+j+n+2} {i*n+j+n+1}\n" for j in range(n - 1)))


def exr(path, w, h, value=0.5):
    """A w × h uncompressed scanline EXR of one grey (float channels B, G, R)."""
    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data
    chans = b"".join(c + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in (b"B", b"G", b"R")) + b"\0"
    box = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    head = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2)
            + attr("channels", "chlist", chans) + attr("compression", "compression", b"\0")
            + attr("dataWindow", "box2i", box) + attr("displayWindow", "box2i", box)
            + attr("lineOrder", "lineOrder", b"\0") + attr("pixelAspectRatio", "float", struct.pack("<f", 1))
            + attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0))
            + attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    line = struct.pack(f"<{3 * w}f", *[value] * (3 * w))
    start = len(head) + 8 * h
    offsets = struct.pack(f"<{h}Q", *[start + y * (8 + len(line)) for y in range(h)])
    body = b"".join(struct.pack("<ii", y, len(line)) + line for y in range(h))
    open(path, "wb").write(head + offsets + body)


def exr_header(b):
    """(attributes {name: (type, offset, size)}, offset just past the header)."""
    assert b[:4] == b"\x76\x2f\x31\x01", "not an EXR file"
    p, attrs = 8, {}
    while b[p] != 0:
        name_end = b.index(b"\0", p)
        type_end = b.index(b"\0", name_end + 1)
        size = struct.unpack_from("<i", b, type_end + 1)[0]
        attrs[b[p:name_end].decode()] = (b[name_end + 1:type_end].decode(), type_end + 5, size)
        p = type_end + 5 + size
    return attrs, p + 1


def exr_window(path, last):
    """Sets the display window to (0, 0)–(last, last)."""
    b = bytearray(open(path, "rb").read())
    attrs, _ = exr_header(b)
    _, at, _ = attrs["displayWindow"]
    struct.pack_into("<ii", b, at + 8, last, last)
    open(path, "wb").write(b)


def unpredict(d):
    """OpenEXR's RLE/ZIP post-processing undone: the byte predictor, then the interleaving."""
    d = bytearray(d)
    for i in range(1, len(d)):
        d[i] = (d[i - 1] + d[i] - 128) & 0xFF
    half = (len(d) + 1) // 2
    out = bytearray(len(d))
    out[0::2] = d[:half]
    out[1::2] = d[half:]
    return out


def rle_decode(c):
    out, p = bytearray(), 0
    while p < len(c):
        n = struct.unpack_from("b", c, p)[0]
        p += 1
        if n < 0:
            out += c[p:p - n]
            p -= n
        else:
            out += bytes([c[p]]) * (n + 1)
            p += 1
    return out


def exr_nan(path, pixels=4):
    """Writes NaN into the `sum.R/G/B` channels of the first `pixels` pixels of the first
    block (tile or scanlines) of an EXR (RLE, ZIPS, ZIP or none): that block is stored
    uncompressed (as OpenEXR does when compression does not pay) and the offsets moved."""
    b = bytes(open(path, "rb").read())
    attrs, p = exr_header(b)
    _, at, size = attrs["channels"]
    chans, q = [], at
    while b[q] != 0:
        e = b.index(b"\0", q)
        chans.append((b[q:e].decode(), struct.unpack_from("<i", b, e + 1)[0]))
        q = e + 17
    comp = b[attrs["compression"][1]]
    x0, y0, x1, y1 = struct.unpack_from("<iiii", b, attrs["dataWindow"][1])
    w, h = x1 - x0 + 1, y1 - y0 + 1
    if "tiles" in attrs:  # the first tile: its coordinates (4 ints) before its size
        tw, th = struct.unpack_from("<II", b, attrs["tiles"][1])
        head, cols, rows = 16, min(tw, w), min(th, h)
        nchunks = struct.unpack_from("<i", b, attrs["chunkCount"][1])[0]
    else:  # the first block of scanlines: its y before its size
        lines = {0: 1, 1: 1, 2: 1, 3: 16}[comp]
        head, cols, rows = 4, w, min(lines, h)
        nchunks = math.ceil(h / lines)
    offsets = list(struct.unpack_from(f"<{nchunks}Q", b, p))
    first = offsets[0]
    csize = struct.unpack_from("<i", b, first + head)[0]
    data = b[first + head + 4:first + head + 4 + csize]
    bpp = sum(2 if t == 1 else 4 for _, t in chans)
    expect = rows * cols * bpp
    if csize == expect:
        raw = bytearray(data)
    elif comp == 1:
        raw = unpredict(rle_decode(data))
    else:
        raw = unpredict(zlib.decompress(data))
    assert len(raw) == expect, (len(raw), expect)
    off = 0  # the block's first line: the channels one after another, `cols` samples each
    for name, t in chans:
        if name in ("sum.R", "sum.G", "sum.B"):
            for i in range(pixels):
                struct.pack_into("<I", raw, off + 4 * i, 0x7FC00000)
        off += cols * (2 if t == 1 else 4)
    chunk = b[first:first + head] + struct.pack("<i", len(raw)) + bytes(raw)
    delta = len(chunk) - (head + 4 + csize)
    offsets = [offsets[0]] + [o + delta for o in offsets[1:]]
    out = b[:p] + struct.pack(f"<{nchunks}Q", *offsets) + chunk + b[first + head + 4 + csize:]
    open(path, "wb").write(out)


def brightest(path):
    """The largest and the median finite value, and the count of non-finite values, of an
    EXR image."""
    try:
        import numpy as np
        import mitsuba as mi
        mi.set_variant("scalar_rgb")
        a = np.array(mi.Bitmap(path), dtype=np.float64)
    except Exception as e:  # no reader: say so
        print(f"unread ({type(e).__name__})")
        return
    fin = np.isfinite(a)
    print(f"brightest {a[fin].max():.4g}, median {np.median(a[fin]):.4g}, {int((~fin).sum())} non-finite")


if __name__ == "__main__":
    cmd, *a = sys.argv[1:]
    if cmd == "png":
        png(a[0], int(a[1]), int(a[2]))
    elif cmd == "soup":
        obj_soup(a[0], int(a[1]), a[2] == "shared")
    elif cmd == "shifted":
        obj_shifted(a[0], int(a[1]))
    elif cmd == "grid":
        obj_grid(a[0], int(a[1]))
    elif cmd == "exr":
        exr(a[0], int(a[1]), int(a[2]))
    elif cmd == "window":
        exr_window(a[0], int(a[1]))
    elif cmd == "nan":
        exr_nan(a[0])
    elif cmd == "brightest":
        brightest(a[0])
PYEOF

# ---- scenes ----------------------------------------------------------------------------

# mesh_scene FILE KIND MESH: one mesh shape at 16 × 16 pixels under a constant environment.
mesh_scene() {
    cat >"$1" <<EOF
<scene version="3.0.0">
  <integrator type="path"/>
  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0,0,4" target="0,0,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
  </sensor>
  <shape type="$2"><string name="filename" value="$3"/></shape>
  <emitter type="constant"/>
</scene>
EOF
}

# cornell_plus FILE XML: the Cornell box with XML added before its closing tag.
cornell_plus() {
    sed '$d' "$CORNELL" | grep -v '^</scene>' >"$1"
    printf '%s\n</scene>\n' "$2" >>"$1"
}

# ---- running ---------------------------------------------------------------------------

# The deepest descendant of process $1 (time → timeout → the program).
leaf() {
    local p=$1 c
    while c=$(pgrep -P "$p" | head -1) && [ -n "$c" ]; do p=$c; done
    echo "$p"
}

# run NAME SIGNAL PHASE LIMIT CMD...: runs CMD in OUT/NAME (stdout, stderr, time report
# there); SIGNAL (INT, TERM or -) is sent once PHASE has begun: `loading` 0.5 s after the
# start, `header` 0.5 s after the first line of stdout (printed just before rendering),
# `threads` samples the thread count at 2 s instead.
run() {
    local name=$1 sig=$2 phase=$3 limit=$4
    shift 4
    if [ -n "${ONLY:-}" ] && ! [[ $name =~ $ONLY ]]; then return; fi  # ONLY=REGEX: a subset
    local d=$OUT/$name
    mkdir -p "$d"
    local so=$d/stdout se=$d/stderr tf=$d/time note=""
    local start ka=5
    [ "$phase" = threads ] && ka=1
    start=$(date +%s.%N)
    (
        cd "$d" || exit 99
        ulimit -v $AS_LIMIT_KB
        exec /usr/bin/time -v -o "$tf" timeout --foreground -k $ka "$limit" "$@" >"$so" 2>"$se"
    ) &
    local bg=$!
    if [ "$phase" = threads ]; then
        sleep 2
        local p
        p=$(leaf $bg)
        local n
        n=$(ps -o nlwp= -p "$p" 2>/dev/null | tr -d ' ')
        if [ -n "$n" ] && [ "$p" != "$bg" ]; then note="$n threads at 2 s"; else note="ended before 2 s"; fi
    elif [ "$sig" != - ]; then
        if [ "$phase" = header ]; then
            local t=0
            while [ ! -s "$so" ] && [ $t -lt $((limit * 10)) ] && kill -0 $bg 2>/dev/null; do
                sleep 0.1
                t=$((t + 1))
            done
            sleep 0.5
        else
            sleep 0.5
        fi
        local p
        p=$(leaf $bg)
        local at
        at=$(echo "$(date +%s.%N) - $start" | bc)
        if [ "$phase" = loading ] && [ -s "$so" ]; then
            note="loaded before the signal; "
        fi
        if kill -0 "$p" 2>/dev/null && [ "$p" != "$bg" ]; then
            kill -"$sig" "$p"
            note="${note}SIG$sig at $(printf %.1f "$at") s ($phase)"
        else
            note="${note}ended before SIG$sig"
        fi
    fi
    # Until it ends: the program's most threads and its peak resident size (VmHWM), sampled
    # every 0.2 s from /proc (a check on the time report).
    local most=0 hwm=0 p2 v
    while kill -0 $bg 2>/dev/null; do
        p2=$(leaf $bg)
        if [ "$p2" != "$bg" ] && [ -r "/proc/$p2/status" ]; then
            v=$(sed -n 's/^Threads:[[:space:]]*//p' "/proc/$p2/status" 2>/dev/null)
            [ -n "$v" ] && [ "$v" -gt $most ] && most=$v
            v=$(sed -n 's/^VmHWM:[[:space:]]*\([0-9]*\).*/\1/p' "/proc/$p2/status" 2>/dev/null)
            [ -n "$v" ] && [ "$v" -gt $hwm ] && hwm=$v
        fi
        sleep 0.2
    done
    [ "$phase" = threads ] && note="$note; at most $most threads seen"
    wait $bg
    local rss status elapsed secs
    rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$tf")
    elapsed=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$tf")
    secs=$(echo "$elapsed" | awk -F: '{ s = 0; for (i = 1; i <= NF; i++) s = s * 60 + $i; printf "%.2f", s }')
    local killed code
    killed=$(sed -n 's/.*Command terminated by signal //p' "$tf")
    code=$(sed -n 's/.*Exit status: //p' "$tf")
    local over
    over=$(echo "$secs >= $limit - 0.2" | bc)
    if [ "$over" = 1 ] && { [ "$code" = 124 ] || [ "$code" = 137 ]; }; then
        status="timeout ($limit s)"
        [ "$code" = 137 ] && status="timeout ($limit s; SIGTERM ignored, SIGKILL $ka s later)"
    elif [ -n "$killed" ]; then
        status="killed by signal $killed"
    else
        status=$code
    fi
    local cpu user sys
    user=$(sed -n 's/.*User time (seconds): //p' "$tf")
    sys=$(sed -n 's/.*System time (seconds): //p' "$tf")
    cpu=$(echo "${user:-0} + ${sys:-0}" | bc)
    local first last
    first=$(grep -a -m 1 -v "^[[:space:]]*$" "$se" | sed -e "s#$G/##g" -e "s#$OUT/##g" | iconv -f utf-8 -t utf-8 -c |
        cut -c1-100 | sed 's/|/\\|/g')
    # The program's last word on stdout when it wrote an image or was interrupted.
    last=$(grep -a -E 'wrote|interrupted' "$so" | tail -n 1 | iconv -f utf-8 -t utf-8 -c | cut -c1-80 |
        sed 's/|/\\|/g')
    [ -n "$last" ] && note="${note:+$note; }stdout: $last"
    if [ -n "${IMAGE:-}" ]; then  # IMAGE=FILE run ...: FILE's brightest value in the note
        local b="no image $IMAGE"
        [ -f "$d/$IMAGE" ] && b="$IMAGE: $(python3 "$PY" brightest "$d/$IMAGE")"
        note="${note:+$note; }$b"
    fi
    # The larger of the time report's peak and the sampled one (the same, but for a program
    # killed before it could be waited for).
    [ "${rss:-0}" -lt "$hwm" ] && rss=$hwm
    printf '| %s | %s | %s | %s | %.0f | %s | %s |\n' "$name" "$status" "$secs" "$cpu" \
        "$(echo "${rss:-0} / 1024" | bc -l)" "${first:+\`$first\`}" "$note"
}

# ---- the cases -------------------------------------------------------------------------

G=$OUT/gen
mkdir -p "$G"
SMALL=(-D res=16 -D spp=1)

echo "| case | exit status | wall s | cpu s | peak MB | first line of stderr | note |"
echo "|---|---|---|---|---|---|---|"

# Degenerate geometry.
python3 "$PY" soup "$G/stacked.obj" 20000 own
mesh_scene "$G/stacked.xml" obj stacked.obj
run stacked-20k - - $LIMIT "$RENDER" "$G/stacked.xml" --spp 1 -o out.exr
python3 "$PY" shifted "$G/shifted.obj" 20000
mesh_scene "$G/shifted.xml" obj shifted.obj
run shifted-coplanar-20k - - $LIMIT "$RENDER" "$G/shifted.xml" --spp 1 -o out.exr
python3 "$PY" soup "$G/identical.obj" 40000 shared
mesh_scene "$G/identical.xml" obj identical.obj
for a in bvh grid kdtree; do
    run "identical-40k-$a" - - $LIMIT "$RENDER" "$G/identical.xml" --accel $a --spp 1 -o out.exr
done

# Memory bounded by what the file holds.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\n' >"$G/sparse.obj"
truncate -s 4G "$G/sparse.obj"
mesh_scene "$G/sparse-obj.xml" obj sparse.obj
run sparse-obj-4GiB - - $LIMIT "$RENDER" "$G/sparse-obj.xml" --spp 1 -o out.exr
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 357913900\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n' >"$G/sparse.ply"
truncate -s 4G "$G/sparse.ply"
mesh_scene "$G/sparse-ply.xml" ply sparse.ply
run sparse-ply-4GiB - - $LIMIT "$RENDER" "$G/sparse-ply.xml" --spp 1 -o out.exr
python3 "$PY" png "$G/t0.png" 8192 8192
shapes=""
for i in 0 1 2 3 4 5; do
    [ $i -gt 0 ] && cp "$G/t0.png" "$G/t$i.png"
    shapes="$shapes
  <shape type=\"rectangle\"><bsdf type=\"diffuse\"><texture type=\"bitmap\" name=\"reflectance\"><string name=\"filename\" value=\"t$i.png\"/></texture></bsdf></shape>"
done
cat >"$G/textures.xml" <<EOF
<scene version="3.0.0"><integrator type="path"/>
  <sensor type="perspective"><float name="fov" value="40"/>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
  </sensor>$shapes
  <emitter type="constant"/>
</scene>
EOF
run textures-6x8192sq - - "${TEXTURES_LIMIT:-$LIMIT}" "$RENDER" "$G/textures.xml" --spp 1 -o out.exr
sed -e 's/name="width" value="\$res"/name="width" value="2048"/' \
    -e 's/name="height" value="\$res"/name="height" value="1408"/' "$CORNELL" >"$G/cornell-2048x1408.xml"
run mlt-2048x1408-depth64 - - $LIMIT "$RENDER" "$G/cornell-2048x1408.xml" --integrator mlt \
    -D max_depth=64 --spp 1 -o out.exr
# The same with 10⁴ bootstrap samples (the default is 10⁵): it finishes on a loaded machine
# within 120 s, so the memory of the rendering phase is seen too.
sed -e 's#<integrator type="path">#<integrator type="mlt"><integer name="bootstrap_samples" value="10000"/>#' \
    "$G/cornell-2048x1408.xml" >"$G/mlt-2048x1408.xml"
run mlt-2048x1408-depth64-bootstrap1e4 - - 120 "$RENDER" "$G/mlt-2048x1408.xml" -D max_depth=64 \
    --spp 1 -o out.exr
run mlt-max-depth-1e9 - - $LIMIT "$RENDER" "$CORNELL" --integrator mlt -D max_depth=1000000000 \
    "${SMALL[@]}" --spp 1 -o out.exr
"$RENDER" "$CORNELL" -D res=16 --spp 2 --samples 0..2 -o "$G/part.exr" >/dev/null 2>&1
cp "$G/part.exr" "$G/window.exr"
python3 "$PY" window "$G/window.exr" 99999
run merge-window-100000sq - - $LIMIT "$MERGE" merged.exr "$G/window.exr"

# Threads.
run threads-100000 - threads 5 "$RENDER" "$CORNELL" "${SMALL[@]}" --threads 100000 -o out.exr
run threads-2^64-1 - threads 5 "$RENDER" "$CORNELL" "${SMALL[@]}" --threads 18446744073709551615 -o out.exr

# Interrupts.
python3 "$PY" grid "$G/grid.obj" 1000
cat >"$G/grid.xml" <<EOF
<scene version="3.0.0"><sensor type="perspective">
  <transform name="to_world"><lookat origin="0.5, 0.5, 3" target="0.5, 0.5, 0" up="0, 1, 0"/></transform>
  <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor><shape type="obj"><string name="filename" value="grid.obj"/></shape>
  <emitter type="point"><point name="position" x="0" y="3" z="3"/></emitter></scene>
EOF
run sigterm-loading TERM loading $LIMIT "$RENDER" "$G/grid.xml" --threads 1 -o out.exr
cat >"$G/white.xml" <<EOF
<scene version="3.0.0"><integrator type="path">
  <integer name="max_depth" value="-1"/><integer name="rr_depth" value="4294967295"/>
  </integrator><sensor type="perspective">
  <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor><shape type="sphere"><float name="radius" value="5"/>
  <bsdf type="twosided"><bsdf type="diffuse"><float name="reflectance" value="1"/></bsdf></bsdf>
  </shape><emitter type="point"><point name="position" x="0" y="1" z="1"/></emitter></scene>
EOF
run rr-depth-2^32-1-sigint INT header $LIMIT "$RENDER" "$G/white.xml" --threads 1 -o out.exr
cat >"$G/bootstrap.xml" <<EOF
<scene version="3.0.0"><integrator type="mlt">
  <integer name="bootstrap_samples" value="4294967295"/><integer name="max_depth" value="4"/>
  </integrator><sensor type="perspective">
  <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
  <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor><shape type="sphere"><bsdf type="diffuse"/></shape>
  <emitter type="point"><point name="position" x="0" y="3" z="3"/></emitter></scene>
EOF
for s in INT TERM; do
    run "mlt-bootstrap-2^32-1-sig$s" $s header $LIMIT "$RENDER" "$G/bootstrap.xml" --threads 1 \
        "${BIG_BUDGET[@]}" -o out.exr
done

# Lights whose power overflows f32, added to the Cornell box.
cornell_plus "$G/point.xml" '<emitter type="point"><point name="position" x="0" y="0.5" z="0.5"/><rgb name="intensity" value="5e37"/></emitter>'
cornell_plus "$G/directional.xml" '<emitter type="directional"><vector name="direction" x="0" y="-0.3" z="-1"/><rgb name="irradiance" value="5e37"/></emitter>'
cornell_plus "$G/spot.xml" '<emitter type="spot"><transform name="to_world"><lookat origin="0, 0.5, 1" target="0, 0, 0" up="0, 1, 0"/></transform><rgb name="intensity" value="3e38"/></emitter>'
python3 "$PY" exr "$G/env.exr" 8 4
cornell_plus "$G/envmap.xml" '<emitter type="envmap"><string name="filename" value="env.exr"/><float name="scale" value="3e38"/></emitter>'
# The box as it is, for the brightest and median values of its image.
IMAGE=out.exr run cornell-alone - - $LIMIT "$RENDER" "$CORNELL" -D res=32 --spp 16 -o out.exr
for l in point directional spot envmap; do
    v=5e37
    [ $l = spot ] || [ $l = envmap ] && v=3e38
    IMAGE=out.exr run "$l-$v" - - $LIMIT "$RENDER" "$G/$l.xml" -D res=32 --spp 16 -o out.exr
done

# merge.
rm -f "$G/fifo.exr"
mkfifo "$G/fifo.exr"
run merge-fifo-part - - $LIMIT "$MERGE" merged.exr "$G/fifo.exr"
cp "$G/part.exr" "$G/nan.exr"
python3 "$PY" nan "$G/nan.exr"
IMAGE=merged.exr run merge-nan-sums - - $LIMIT "$MERGE" merged.exr "$G/nan.exr"
run merge-non-utf8-output - - $LIMIT "$MERGE" $'merged\xff.exr' "$G/part.exr"
run render-non-utf8-output - - $LIMIT "$RENDER" "$CORNELL" "${SMALL[@]}" -o $'caf\xe9.exr'

# Small things.
cornell_plus "$G/include.xml" '<include filename="inc.xml"/>'
printf '<scene>\n<bsdf type="diffuse" id="extra"/>\n</scene>\n' >"$G/inc.xml"
run include-without-version - - $LIMIT "$RENDER" "$G/include.xml" "${SMALL[@]}" -o out.exr
cornell_plus "$G/two-env.xml" '<emitter type="constant"/>
<emitter type="constant"/>'
run two-environments - - $LIMIT "$RENDER" "$G/two-env.xml" "${SMALL[@]}" -o out.exr
cat >"$G/focal.xml" <<EOF
<scene version="3.0.0">
  <sensor type="perspective">
    <string name="focal_length" value="1e-40mm"/>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
  </sensor>
  <shape type="sphere"/>
  <emitter type="constant"/>
</scene>
EOF
run focal-length-1e-40mm - - $LIMIT "$RENDER" "$G/focal.xml" --spp 1 -o out.exr
run spp-0 - - $LIMIT "$RENDER" "$CORNELL" -D res=16 --spp 0 -o out.exr

rm -f "$G/sparse.obj" "$G/sparse.ply" "$G/fifo.exr"
