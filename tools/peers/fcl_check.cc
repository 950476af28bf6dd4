// tools/peers.sh: FCL's discrete collision check (Debian libfcl-dev, FCL 0.7, MoveIt's collision engine) of the motion
// BM_CheckBuildHourUrdfArm checks, built by the script, not part of the project build. It reads what that benchmark
// exports with WAAM_CHECK_EXPORT (check_cell.txt: the cell's collision shapes in their geom frames, the meshes'
// triangles as MuJoCo loaded them from the URDF's STL files, the pairs MuJoCo tests; check_poses.bin: every moving
// shape's world pose at every sample, from the cell's forward kinematics) and checks every sample as MoveIt does:
// the poses set, a dynamic AABB tree broadphase, and a boolean narrow phase (one contact) on the tested pairs only;
// meshes as OBBRSS bounding-volume trees of their triangles, primitives as FCL's own shapes (the floor plane as
// a slab, see kPlaneDepthMm). The poses are given:
// the time excludes the forward kinematics and the IK that waam's figure includes.
// Usage: fcl_check <export_dir> [runs]; prints one line of key=value figures.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fcl/fcl.h>

namespace {

// MuJoCo's plane is the half-space z <= 0 of its frame; FCL's dynamic AABB tree cannot hold a half-space's infinite
// box, so the floor is a slab this deep below the plane over the plane's drawn size (8 x 8 m here, the whole cell).
constexpr double kPlaneDepthMm = 100.0;

double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Shape {
  std::string type, body;
  bool moving = false;
  double size[3] = {0, 0, 0};
  fcl::Transform3d pose = fcl::Transform3d::Identity();
  std::vector<fcl::Vector3d> vertices;
  std::vector<fcl::Triangle> triangles;
};

[[noreturn]] void Fail(const std::string& why) {
  std::cerr << "fcl_check: " << why << "\n";
  std::exit(1);
}

std::shared_ptr<fcl::CollisionGeometryd> GeometryOf(const Shape& s) {
  const double* z = s.size;
  if (s.type == "sphere") return std::make_shared<fcl::Sphered>(z[0]);
  if (s.type == "capsule") return std::make_shared<fcl::Capsuled>(z[0], 2.0 * z[1]);
  if (s.type == "cylinder") return std::make_shared<fcl::Cylinderd>(z[0], 2.0 * z[1]);
  if (s.type == "box") return std::make_shared<fcl::Boxd>(2.0 * z[0], 2.0 * z[1], 2.0 * z[2]);
  if (s.type == "ellipsoid") return std::make_shared<fcl::Ellipsoidd>(z[0], z[1], z[2]);
  if (s.type == "plane") return std::make_shared<fcl::Boxd>(2.0 * z[0], 2.0 * z[1], kPlaneDepthMm);  // see main
  if (s.type == "mesh") {
    auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
    bvh->beginModel();
    bvh->addSubModel(s.vertices, s.triangles);
    bvh->endModel();
    return bvh;
  }
  Fail("unknown shape type " + s.type);
}

// The pairs MuJoCo tests, and the contacts found.
struct Filter {
  std::set<std::pair<int, int>> pairs;
  std::size_t narrow = 0, contacts = 0;
};

int IndexOf(fcl::CollisionObjectd* o) { return static_cast<int>(reinterpret_cast<std::intptr_t>(o->getUserData())); }

bool Callback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
  Filter& f = *static_cast<Filter*>(data);
  const int a = std::min(IndexOf(o1), IndexOf(o2)), b = std::max(IndexOf(o1), IndexOf(o2));
  if (!f.pairs.count({a, b})) return false;
  ++f.narrow;
  fcl::CollisionRequestd request(1, false);
  fcl::CollisionResultd result;
  fcl::collide(o1, o2, request, result);
  if (result.isCollision()) ++f.contacts;
  return false;  // every pair, as a check that reports all contacts does
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) Fail("usage: fcl_check <export_dir> [runs]");
  const std::string dir = argv[1];
  const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  std::ifstream in(dir + "/check_cell.txt");
  if (!in) Fail("cannot read " + dir + "/check_cell.txt");
  std::string line, word;
  std::getline(in, line);  // comment
  std::size_t n = 0;
  in >> word >> n;
  std::vector<Shape> shapes(n);
  for (Shape& s : shapes) {
    std::size_t nv = 0, nf = 0;
    in >> word >> s.type >> s.body >> s.moving >> s.size[0] >> s.size[1] >> s.size[2] >> nv >> nf >> word;
    fcl::Matrix3d R;
    fcl::Vector3d t;
    in >> R(0, 0) >> R(0, 1) >> R(0, 2) >> R(1, 0) >> R(1, 1) >> R(1, 2) >> R(2, 0) >> R(2, 1) >> R(2, 2) >> t[0] >>
        t[1] >> t[2];
    s.pose.linear() = R;
    s.pose.translation() = t;
    if (s.type == "plane") s.pose.translation() -= 0.5 * kPlaneDepthMm * R.col(2);
    for (std::size_t i = 0; i < nv; ++i) {
      fcl::Vector3d v;
      in >> word >> v[0] >> v[1] >> v[2];
      s.vertices.push_back(v);
    }
    for (std::size_t i = 0; i < nf; ++i) {
      int a, b, c;
      in >> word >> a >> b >> c;
      s.triangles.emplace_back(a, b, c);
    }
  }
  Filter filter;
  std::size_t npairs = 0;
  in >> word >> npairs;
  for (std::size_t i = 0; i < npairs; ++i) {
    int a, b;
    in >> a >> b;
    filter.pairs.insert({std::min(a, b), std::max(a, b)});
  }
  std::size_t samples = 0;
  in >> word >> samples >> word;
  std::vector<int> moving;
  for (int i; in >> i;) moving.push_back(i);
  if (!in.eof() || shapes.empty()) Fail("malformed " + dir + "/check_cell.txt");

  std::ifstream bin(dir + "/check_poses.bin", std::ios::binary);
  std::vector<float> poses(samples * moving.size() * 12);
  bin.read(reinterpret_cast<char*>(poses.data()), static_cast<std::streamsize>(poses.size() * sizeof(float)));
  if (!bin) Fail("cannot read " + std::to_string(samples) + " samples from " + dir + "/check_poses.bin");

  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::vector<fcl::CollisionObjectd*> raw;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    objects.push_back(std::make_unique<fcl::CollisionObjectd>(GeometryOf(shapes[i]), shapes[i].pose));
    objects.back()->setUserData(reinterpret_cast<void*>(static_cast<std::intptr_t>(i)));
    objects.back()->computeAABB();
    raw.push_back(objects.back().get());
  }
  fcl::DynamicAABBTreeCollisionManagerd manager;
  manager.registerObjects(raw);
  manager.setup();

  double best = 1e300;
  std::size_t narrow = 0, contacts = 0;
  for (int run = 0; run < runs; ++run) {
    filter.narrow = filter.contacts = 0;
    const double t0 = CpuSeconds();
    for (std::size_t k = 0; k < samples; ++k) {
      const float* row = poses.data() + k * moving.size() * 12;
      for (std::size_t m = 0; m < moving.size(); ++m, row += 12) {
        fcl::Transform3d X = fcl::Transform3d::Identity();
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 3; ++c) X.linear()(r, c) = row[3 * r + c];
          X.translation()[r] = row[9 + r];
        }
        fcl::CollisionObjectd* o = objects[moving[m]].get();
        o->setTransform(X);
        o->computeAABB();
      }
      manager.update();
      manager.collide(&filter, Callback);
    }
    best = std::min(best, CpuSeconds() - t0);
    narrow = filter.narrow;
    contacts = filter.contacts;
  }
  std::printf("fcl shapes=%zu moving=%zu pairs=%zu samples=%zu narrow_phase=%zu contacts=%zu cpu_s=%.4f us_per_sample=%.3f\n",
              shapes.size(), moving.size(), filter.pairs.size(), samples, narrow, contacts, best,
              1e6 * best / static_cast<double>(samples));
  return 0;
}
