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
