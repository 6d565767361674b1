"""Loads exported MJCF files with the pinned MuJoCo and reports what the tests check.

Usage: check_model.py FILE.xml [FILE.xml ...]

For each file: load it, reset to its keyframe "touchdown", run the forward dynamics once, and
print one JSON line with the model's sizes, element names, the secondary tendons' lengths (m),
the footpad sites' heights (m), the number of active contacts and each footpad contact's
condim. Exits non-zero, naming the file, if a file does not load.
"""

import json
import sys

import mujoco


def report(path):
    model = mujoco.MjModel.from_xml_path(path)
    data = mujoco.MjData(model)
    key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "touchdown")
    if key < 0:
        raise ValueError("no keyframe named 'touchdown'")
    mujoco.mj_resetDataKeyframe(model, data, key)
    mujoco.mj_forward(model, data)

    def names(kind, count):
        return [mujoco.mj_id2name(model, kind, i) for i in range(count)]

    geoms = names(mujoco.mjtObj.mjOBJ_GEOM, model.ngeom)
    footpads = [i for i, g in enumerate(geoms) if g and g.endswith("_footpad")]
    return {
        "file": path,
        "nq": int(model.nq),
        "nv": int(model.nv),
        "bodies": names(mujoco.mjtObj.mjOBJ_BODY, model.nbody),
        "joints": names(mujoco.mjtObj.mjOBJ_JOINT, model.njnt),
        "tendons": names(mujoco.mjtObj.mjOBJ_TENDON, model.ntendon),
        "actuators": names(mujoco.mjtObj.mjOBJ_ACTUATOR, model.nu),
        "tendon_lengths_m": [float(x) for x in data.ten_length],
        "footpad_heights_m": [float(data.geom_xpos[i][2]) for i in footpads],
        "footpad_condim": [int(model.geom_condim[i]) for i in footpads],
        "contacts": int(data.ncon),
        "timestep_s": float(model.opt.timestep),
    }


def main(paths):
    for path in paths:
        try:
            print(json.dumps(report(path)))
        except Exception as e:  # noqa: BLE001 - report any loading error with its file
            print(f"check_model.py: {path}: {e}", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
