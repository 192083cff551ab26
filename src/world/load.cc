// SPDX-License-Identifier: Apache-2.0
// Loading an MJCF scene into a World: MuJoCo's loader, one-line errors, the pointer body check.
#include <fcntl.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <mutex>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>

#include "mrh/core/error.h"
#include "mrh/core/validate.h"
#include "world/world_impl.h"

namespace mrh::world {
namespace {

// MuJoCo's loader messages span several lines ("XML Error: ...\n\nElement 'foo', line 6\n"):
// join the non-empty lines with single spaces.
std::string OneLine(const char* message) {
  std::istringstream lines(message);
  std::string line;
  std::string out;
  while (std::getline(lines, line)) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    const auto last = line.find_last_not_of(" \t\r");
    if (!out.empty()) out += ' ';
    out += line.substr(first, last - first + 1);
  }
  return out.empty() ? std::string("MuJoCo could not load the scene (no message)") : out;
}

// The scene whose MuJoCo call is running on this thread (internal::MujocoScope), for errors.
thread_local const std::string* current_scene = nullptr;

// MuJoCo's default error handler prints, appends to MUJOCO_LOG.TXT and exits the process. This
// one throws instead, naming the scene: a catchable mrh::RuntimeError (exit code 1), or a
// SceneError while the scene loads (exit code 2).
[[noreturn]] void ThrowMujocoError(const char* message) {
  const std::string scene = current_scene != nullptr ? *current_scene : "(unknown scene)";
  const bool out_of_memory = std::string_view(message).find("out of memory") != std::string::npos;
  throw RuntimeError(scene + ": MuJoCo error: " + OneLine(message) +
                     "; the simulation cannot continue (" +
                     (out_of_memory ? "its arena is full: raise <size memory=...> in the scene, or "
                                      "remove it and mrhaptics sizes the arena"
                                    : "check the scene's sizes and solver settings") +
                     ")");
}

// MuJoCo's default warning handler prints to stdout and appends to MUJOCO_LOG.TXT in the working
// directory. Every warning it raises while stepping is also counted in mjData::warning, which
// World::SimulatorWarnings() reports once at the end of a run (and summary.json lists), so the
// handler only has to stay quiet.
void InstallMujocoHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_warning = [](const char*) {};
    mju_user_error = [](const char* message) {
      ThrowMujocoError(message);
    };
  });
}

// Bounds of the scene as MuJoCo read it (docs/session-format.md, "Ranges").
constexpr double kMaxGravity = 1e3;  // m/s^2, per component
constexpr double kMaxExtent = 1e4;   // m: positions, sizes, mesh vertices
constexpr double kMaxMass = 1e6;     // kg

std::string Name(const mjModel& m, mjtObj type, int id, const char* kind) {
  return std::string(kind) + " " + internal::Describe(m, type, id);
}

// Throws unless the `count` numbers at `v` are finite and within [-limit, limit].
void CheckNumbers(const mjtNum* v, int count, double limit, const std::string& origin,
                  const std::string& what, const char* unit) {
  for (int i = 0; i < count; ++i) {
    if (std::isfinite(v[i]) && std::abs(v[i]) <= limit) continue;
    throw SceneError(origin + ": " + what + " = " + FormatNumbers(v, count) + " " + unit +
                     "; expected finite values within +-" + FormatNumber(limit) + " " + unit +
                     " (fix the scene)");
  }
}

// NaN, inf or astronomically large numbers in the scene break the collision and rendering code
// (FCL asserts, the perturbation measurements divide by them); refuse them at load.
void CheckSceneNumbers(const mjModel& m, const std::string& origin) {
  CheckNumbers(m.opt.gravity, 3, kMaxGravity, origin, "<option gravity>", "m/s^2");
  for (int g = 0; g < m.ngeom; ++g) {
    const std::string geom = Name(m, mjOBJ_GEOM, g, "geom");
    CheckNumbers(m.geom_size + 3 * g, 3, kMaxExtent, origin, geom + " size", "m");
    CheckNumbers(m.geom_pos + 3 * g, 3, kMaxExtent, origin, geom + " pos", "m");
  }
  for (int b = 0; b < m.nbody; ++b) {
    const std::string body = Name(m, mjOBJ_BODY, b, "body");
    CheckNumbers(m.body_pos + 3 * b, 3, kMaxExtent, origin, body + " pos", "m");
    CheckNumbers(m.body_quat + 4 * b, 4, kMaxExtent, origin, body + " quat", "");
    CheckNumbers(m.body_mass + b, 1, kMaxMass, origin, body + " mass", "kg");
    CheckNumbers(m.body_inertia + 3 * b, 3, kMaxMass * kMaxExtent, origin, body + " inertia",
                 "kg*m^2");
  }
  for (int v = 0; v < m.nmeshvert; ++v) {
    const mjtNum p[3] = {m.mesh_vert[3 * v], m.mesh_vert[3 * v + 1], m.mesh_vert[3 * v + 2]};
    CheckNumbers(p, 3, kMaxExtent, origin, "mesh vertex #" + std::to_string(v), "m");
  }
}

// A mesh is concave when one of its faces has vertices on both sides of its plane (a face of a
// convex mesh has them all on one side). Collision and rendering use the convex hull.
bool IsConcave(const mjModel& m, int mesh) {
  const int first = m.mesh_vertadr[mesh];
  const int count = m.mesh_vertnum[mesh];
  auto vertex = [&](int i) {
    const float* v = m.mesh_vert + 3 * (first + i);
    return Vec3(v[0], v[1], v[2]);
  };
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (int i = 0; i < count; ++i) {
    lo = lo.cwiseMin(vertex(i));
    hi = hi.cwiseMax(vertex(i));
  }
  const double tolerance = 1e-6 * (hi - lo).norm();
  for (int f = m.mesh_faceadr[mesh]; f < m.mesh_faceadr[mesh] + m.mesh_facenum[mesh]; ++f) {
    const int* face = m.mesh_face + 3 * f;
    if (face[0] >= count || face[1] >= count || face[2] >= count) continue;
    const Vec3 a = vertex(face[0]);
    const Vec3 n = (vertex(face[1]) - a).cross(vertex(face[2]) - a);
    if (!(n.norm() > 0.0)) continue;
    const Vec3 u = n.normalized();
    bool above = false;
    bool below = false;
    for (int i = 0; i < count; ++i) {
      const double d = u.dot(vertex(i) - a);
      above = above || d > tolerance;
      below = below || d < -tolerance;
    }
    if (above && below) return true;
  }
  return false;
}

// Warnings about the scene that mean the physics differs from what the MJCF says.
std::vector<std::string> SceneWarnings(const mjModel& m, const std::string& origin) {
  std::vector<std::string> warnings;
  for (int mesh = 0; mesh < m.nmesh; ++mesh) {
    if (!IsConcave(m, mesh)) continue;
    warnings.push_back(origin + ": " + Name(m, mjOBJ_MESH, mesh, "mesh") +
                       " is concave and is replaced by its convex hull for collision and "
                       "haptic rendering; if its hollows matter, build the object as one body of "
                       "several convex geoms (see scenes/compound_mug.xml)");
  }
  return warnings;
}

// MuJoCo's mesh compiler runs qhull with stderr as its error file, so a degenerate mesh (equal,
// collinear or coplanar points) prints a dozen lines before MuJoCo's own error. While the
// loader runs, stdout and stderr point at /dev/null; MuJoCo's message still reaches the error
// buffer, which becomes the one-line SceneError.
class QuietStdio {
 public:
  QuietStdio() {
    std::fflush(stdout);
    std::fflush(stderr);
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null < 0) return;
    saved_out_ = ::dup(STDOUT_FILENO);
    saved_err_ = ::dup(STDERR_FILENO);
    if (saved_out_ >= 0) ::dup2(null, STDOUT_FILENO);
    if (saved_err_ >= 0) ::dup2(null, STDERR_FILENO);
    ::close(null);
  }

  ~QuietStdio() {
    std::fflush(stdout);
    std::fflush(stderr);
    Restore(saved_out_, STDOUT_FILENO);
    Restore(saved_err_, STDERR_FILENO);
  }

  QuietStdio(const QuietStdio&) = delete;
  QuietStdio& operator=(const QuietStdio&) = delete;

 private:
  static void Restore(int saved, int fd) {
    if (saved < 0) return;
    ::dup2(saved, fd);
    ::close(saved);
  }

  int saved_out_ = -1;
  int saved_err_ = -1;
};

// `text` is the scene's MJCF, for the memory sizes it sets itself (internal::SizeArena).
internal::ModelPtr LoadOrThrow(const char* file, const mjVFS* vfs, const std::string& origin,
                               const std::string& text) {
  InstallMujocoHandlers();
  std::array<char, 1024> error{};
  internal::ModelPtr model;
  try {
    const internal::MujocoScope scope(origin);
    const QuietStdio quiet;
    model.reset(mj_loadXML(file, vfs, error.data(), static_cast<int>(error.size())));
  } catch (const RuntimeError& e) {
    throw SceneError(e.what());
  }
  if (!model) throw SceneError(origin + ": " + OneLine(error.data()));
  internal::SizeArena(model.get(), internal::FindExplicitSizes(text));
  return model;
}

std::string ReadScene(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string PointerFix(const std::string& name) {
  return "add <body name=\"" + name +
         "\" mocap=\"true\"> as a child of <worldbody>, or set pointer.body in the session to the "
         "scene's mocap body";
}

// The pointer must be a mocap body. Its geoms stop colliding inside MuJoCo: the haptic rendering
// owns the pointer's contacts.
int SetUpPointer(mjModel* m, const std::string& origin, const LoadOptions& options,
                 const std::string& name, std::vector<BodyInfo>* bodies,
                 std::vector<GeomInfo>* geoms) {
  if (name.empty()) return -1;
  const int body = mj_name2id(m, mjOBJ_BODY, name.c_str());
  if (body < 0) {
    throw SceneError(origin + ": pointer body '" + name + "' not found; " + PointerFix(name));
  }
  // A tool that collides inside MuJoCo (virtual-coupling); only the first pointer can be one.
  if (options.dynamic_pointer && name == options.pointer_body) {
    internal::SetUpDynamicPointer(m, body, options, origin,
                                  &(*bodies)[static_cast<std::size_t>(body)]);
    return body;
  }
  if (m->body_mocapid[body] < 0) {
    throw SceneError(origin + ": pointer body '" + name + "' is not a mocap body; " +
                     PointerFix(name));
  }
  for (int g = m->body_geomadr[body]; g >= 0 && g < m->body_geomadr[body] + m->body_geomnum[body];
       ++g) {
    m->geom_contype[g] = 0;
    m->geom_conaffinity[g] = 0;
    (*geoms)[static_cast<std::size_t>(g)].collides = false;
  }
  internal::RefreshBodyCollisionMasks(m, body);
  // Explicit <contact><pair> elements bypass contype/conaffinity.
  for (int p = 0; p < m->npair; ++p) {
    if (m->geom_bodyid[m->pair_geom1[p]] == body || m->geom_bodyid[m->pair_geom2[p]] == body) {
      throw SceneError(origin + ": <contact><pair> #" + std::to_string(p) +
                       " involves a geom of pointer body '" + name +
                       "'; remove the pair (the haptic rendering handles the pointer's contacts)");
    }
  }
  return body;
}

}  // namespace

World::World(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;
World::~World() = default;

World World::LoadFile(const std::filesystem::path& path, const LoadOptions& options) {
  const std::string origin = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw SceneError(origin + ": scene file not found (working directory " +
                     std::filesystem::current_path(ec).string() +
                     "); check the path or run from the directory it is relative to");
  }
  if (options.dynamic_pointer) {
    // The rewritten text keeps the scene's folder for its relative asset paths.
    return LoadText(internal::MakePointerDynamic(ReadScene(path), options.pointer_body, origin),
                    options, origin, path.parent_path());
  }
  auto impl = std::make_unique<Impl>();
  internal::InitializeState(LoadOrThrow(origin.c_str(), nullptr, origin, ReadScene(path)), origin,
                            options, impl.get());
  return World(std::move(impl));
}

World World::LoadString(const std::string& xml, const LoadOptions& options,
                        const std::string& origin) {
  return LoadText(xml, options, origin, {});
}

World World::LoadText(const std::string& xml, const LoadOptions& options, const std::string& origin,
                      const std::filesystem::path& directory) {
  // Staged as a file of a virtual file system, so that MuJoCo's one loader serves both paths.
  // MuJoCo resolves relative asset paths against the staged file's folder.
  const std::string name = (directory / "mrh_scene.xml").string();
  if (xml.empty()) {
    throw SceneError(origin + ": the scene text is empty; expected MJCF (<mujoco>...</mujoco>)");
  }
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());

  struct VfsCleanup {
    mjVFS* vfs;

    ~VfsCleanup() { mj_deleteVFS(vfs); }
  } cleanup{vfs.get()};

  if (xml.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()) ||
      mj_addBufferVFS(vfs.get(), name.c_str(), xml.data(), static_cast<int>(xml.size())) != 0) {
    throw SceneError(origin + ": cannot stage the scene text for MuJoCo (" +
                     std::to_string(xml.size()) + " bytes)");
  }
  auto impl = std::make_unique<Impl>();
  internal::InitializeState(LoadOrThrow(name.c_str(), vfs.get(), origin, xml), origin, options,
                            impl.get());
  return World(std::move(impl));
}

namespace internal {

MujocoScope::MujocoScope(const std::string& scene) : previous_(current_scene) {
  current_scene = &scene;
}

MujocoScope::~MujocoScope() {
  current_scene = previous_;
}

}  // namespace internal

const std::string& World::origin() const {
  return impl_->origin;
}

const std::vector<std::string>& World::LoadWarnings() const {
  return impl_->load_warnings;
}

namespace internal {

void InitializeState(ModelPtr model, const std::string& origin, const LoadOptions& options,
                     WorldState* impl) {
  impl->origin = origin;
  const MujocoScope scope(impl->origin);
  CheckSceneNumbers(*model, origin);
  impl->load_warnings = SceneWarnings(*model, origin);
  DescribeModel(*model, origin, &impl->bodies, &impl->geoms);
  impl->pointer_body =
      SetUpPointer(model.get(), origin, options, options.pointer_body, &impl->bodies, &impl->geoms);
  // Further pointers stop colliding inside MuJoCo too: pointers never touch.
  for (const std::string& name : options.more_pointer_bodies) {
    SetUpPointer(model.get(), origin, options, name, &impl->bodies, &impl->geoms);
  }
  try {
    impl->data.reset(mj_makeData(model.get()));
  } catch (const RuntimeError&) {
    impl->data.reset();  // MuJoCo reports a failed allocation as an error
  }
  if (!impl->data) {
    throw SceneError(origin + ": MuJoCo could not allocate the scene's data (arena " +
                     std::to_string(model->narena) +
                     " bytes); lower <size memory> or remove it (mrhaptics then sizes the arena "
                     "from the scene)");
  }
  if (options.dynamic_pointer) mj_setConst(model.get(), impl->data.get());
  // B2 computes every contact itself (contact-volume penalty, physics::ContactVolumePhysics).
  if (options.penalty_contacts) model->opt.disableflags |= mjDSBL_CONTACT;
  impl->model = std::move(model);
  impl->snapshot_size = SnapshotSize(*impl->model);
  // Everything derived from qpos (poses, contacts) is valid right after loading.
  mj_forward(impl->model.get(), impl->data.get());
}

}  // namespace internal
}  // namespace mrh::world
