# The book-3 Cornell box (RayTracing/raytracing.github.io, src/TheRestOfYourLife/main.cc) as a
# Mitsuba 3 scene, rendered by Mitsuba's path tracer for `rtl bench compare`.
#
# usage: python cornell_mitsuba.py VARIANT WIDTH SPP MAX_DEPTH THREADS OUT_PREFIX SEED [SEED ...]
#
# Writes OUT_PREFIX-SEED.pfm (linear RGB, the standard colour PFM, rows bottom-to-top) for each seed
# and prints one line `seed S seconds T cpu C` per render: T is the wall clock of `mi.render` plus the
# evaluation of its result, C the processor time of the process (all threads) meanwhile (the first
# render of a process also compiles Mitsuba's kernels).
import struct
import sys
import time

import drjit as dr
import mitsuba as mi
import numpy as np

variant, width, spp, max_depth, threads, prefix = sys.argv[1:7]
seeds = [int(s) for s in sys.argv[7:]]
width, spp, max_depth, threads = int(width), int(spp), int(max_depth), int(threads)
mi.set_variant(variant)
if hasattr(dr, "set_thread_count"):
    dr.set_thread_count(threads)


def matrix(columns, origin):
    """The 4x4 affine map x -> [c0 c1 c2] x + origin."""
    m = np.eye(4)
    for i, c in enumerate(columns):
        m[:3, i] = c
    m[:3, 3] = origin
    return mi.ScalarTransform4f(m.tolist())


def quad(q, u, v, bsdf=None, emit=None):
    """The book's quad Q + a u + b v, a, b in [0, 1]: Mitsuba's rectangle [-1, 1]^2 x {0} (normal +z)
    mapped by (u / 2, v / 2, n) about the centre; its normal is then u x v, as the book's."""
    q, u, v = (np.array(x, dtype=float) for x in (q, u, v))
    n = np.cross(u, v)
    n /= np.linalg.norm(n)
    shape = {"type": "rectangle", "to_world": matrix([u / 2, v / 2, n], q + (u + v) / 2)}
    if bsdf is not None:
        shape["bsdf"] = bsdf
    if emit is not None:
        # Mitsuba's area lights emit on the side of the normal only, like the book-3 light.
        shape["emitter"] = {"type": "area", "radiance": {"type": "rgb", "value": emit}}
        shape["bsdf"] = {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0, 0, 0]}}
    return shape


def diffuse(rgb):
    # The book's Lambertian scatters on both sides; Mitsuba's diffuse BSDF is one-sided.
    return {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": rgb}}}


red, white, green = diffuse([0.65, 0.05, 0.05]), diffuse([0.73, 0.73, 0.73]), diffuse([0.12, 0.45, 0.15])
c, s = np.cos(np.radians(15.0)), np.sin(np.radians(15.0))
rot_y = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
half = np.array([82.5, 165.0, 82.5])
# The box [0, 165] x [0, 330] x [0, 165], rotated by 15 degrees about y, then moved by (265, 0, 295):
# the cube [-1, 1]^3 scaled by its half extents about its centre, then the same rotation and move.
box_cols = [rot_y[:, i] * half[i] for i in range(3)]
box_origin = rot_y @ half + np.array([265.0, 0.0, 295.0])

scene = mi.load_dict(
    {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": max_depth},
        "sensor": {
            "type": "perspective",
            "fov": 40.0,
            "fov_axis": "y",
            "to_world": mi.ScalarTransform4f().look_at(
                origin=[278, 278, -800], target=[278, 278, 0], up=[0, 1, 0]
            ),
            "sampler": {"type": "independent", "sample_count": spp},
            "film": {
                "type": "hdrfilm",
                "width": width,
                "height": width,
                "rfilter": {"type": "box"},
                "pixel_format": "rgb",
            },
        },
        "green": quad([555, 0, 0], [0, 0, 555], [0, 555, 0], green),
        "red": quad([0, 0, 555], [0, 0, -555], [0, 555, 0], red),
        "ceiling": quad([0, 555, 0], [555, 0, 0], [0, 0, 555], white),
        "floor": quad([0, 0, 555], [555, 0, 0], [0, 0, -555], white),
        "back": quad([555, 0, 555], [-555, 0, 0], [0, 555, 0], white),
        "light": quad([213, 554, 227], [130, 0, 0], [0, 0, 105], emit=[15, 15, 15]),
        "box": {"type": "cube", "to_world": matrix(box_cols, box_origin), "bsdf": white},
        "glass": {
            "type": "sphere",
            "center": [190, 90, 190],
            "radius": 90.0,
            "bsdf": {"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0},
        },
    }
)


def write_pfm(path, rgb):
    h, w, _ = rgb.shape
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (w, h))
        f.write(np.ascontiguousarray(rgb[::-1], dtype="<f4").tobytes())


for seed in seeds:
    start, cpu = time.perf_counter(), time.process_time()
    image = mi.render(scene, seed=seed, spp=spp)
    dr.eval(image)
    rgb = np.array(image, dtype=np.float32)[:, :, :3]
    seconds, cpu = time.perf_counter() - start, time.process_time() - cpu
    write_pfm("%s-%d.pfm" % (prefix, seed), rgb)
    print("seed %d seconds %.6f cpu %.6f" % (seed, seconds, cpu), flush=True)
