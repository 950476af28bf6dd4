"""Where the tests find the source tree and the built waam (set by tests/CMakeLists.txt for CTest)."""
import os
import pathlib

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("WAAM_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
WAAM_BINARY = os.environ.get("WAAM_BINARY", str(SOURCE_DIR / "build" / "waam"))


@pytest.fixture
def scenarios():
    return SOURCE_DIR / "scenarios"


@pytest.fixture
def tiny(tmp_path):
    """A two-layer block that plans, checks and builds in well under a second."""
    path = tmp_path / "tiny.yaml"
    path.write_text("""name: tiny
part:
  generator: {type: box, size_mm: [30, 20, 3]}
slicing: {type: planar, layer_height_mm: 1.5}
path: {pattern: contour, bead_width_mm: 6}
process: {travel_speed_mm_min: 400, wire_feed_mm_min: 3200}
simulation: {voxel_mm: 1.0}
""")
    return path


TINY_THERMAL = {
    "name": "tiny_thermal",
    "part": {"generator": {"type": "box", "size_mm": [30, 8, 4]}},
    "slicing": {"type": "planar", "layer_height_mm": 2.0},
    "path": {"pattern": "zigzag", "bead_width_mm": 6},
    "process": {"travel_speed_mm_min": 400, "wire_feed_mm_min": 3200,
                "arc": {"voltage_v": 14.5, "current_a": 125}, "interpass": {"max_c": 300, "at": "next_start"}},
    "thermal": {"material": "mild_steel", "substrate": {"size_mm": [60, 30, 6], "material": "mild_steel"},
                "cell_mm": 2.0, "probes": {"plate": [0, 10, -2], "wall": [0, 0, 3]}},
}


@pytest.fixture
def tiny_thermal():
    """A two-layer bar on a small plate with two probes: the thermal model runs in about half a second."""
    import copy
    return copy.deepcopy(TINY_THERMAL)


def run_cli(*args):
    """Runs the built waam; returns its completed process (check=True)."""
    import subprocess
    return subprocess.run([WAAM_BINARY, *[str(a) for a in args]], check=True, capture_output=True, text=True)


def files_under(folder):
    """The files under `folder`, relative, sorted (the output lock aside)."""
    folder = pathlib.Path(folder)
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*") if p.is_file() and p.name != ".waam.lock")
