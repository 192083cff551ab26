// SPDX-License-Identifier: Apache-2.0
// Loading an MJCF scene into a World: MuJoCo's loader, one-line errors, the pointer body check.
#include <mujoco/mujoco.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <sstream>
#include <string>
#include <system_error>

#include "mrh/core/error.h"
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

// MuJoCo's default warning handler prints to stdout and appends to MUJOCO_LOG.TXT in the working
// directory. Every warning it raises while stepping is also counted in mjData::warning, which
// World::SimulatorWarnings() reports, so the handler only has to stay quiet.
void SilenceMujocoWarnings() {
  static std::once_flag once;
  std::call_once(once, [] { mju_user_warning = [](const char*) {}; });
}

// `text` is the scene's MJCF, for the buffer sizes it sets itself (internal::SizeBuffers).
internal::ModelPtr LoadOrThrow(const char* file, const mjVFS* vfs, const std::string& origin,
                               const std::string& text) {
  SilenceMujocoWarnings();
  std::array<char, 1024> error{};
  internal::ModelPtr model(mj_loadXML(file, vfs, error.data(), static_cast<int>(error.size())));
  const internal::ExplicitSizes sizes = internal::FindExplicitSizes(text);
  if (!model && sizes.njmax && std::strstr(error.data(), "could not create mjData") != nullptr) {
    // MuJoCo's compiler allocates data with the scene's own sizes (model_size.cc's limit).
    throw SceneError(origin + ": MuJoCo 2.2.2 could not allocate its data for the scene's <size "
                     "njmax>: its dense constraint arrays (njmax x dofs, njmax x njmax) must stay "
                     "under 2.1 GB; lower njmax or remove it (mrhaptics then sizes it from the "
                     "scene)");
  }
  if (!model) throw SceneError(origin + ": " + OneLine(error.data()));
  internal::SizeBuffers(model.get(), sizes, origin);
  return model;
}

std::string ReadScene(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string PointerFix(const std::string& name) {
  return "add <body name=\"" + name +
         "\" mocap=\"true\"> with a sphere geom as a child of <worldbody>, or name the pointer in "
         "LoadOptions::pointer_body";
}

// The pointer must be a mocap body. Its geoms stop colliding inside MuJoCo: the haptic rendering
// owns the pointer's contacts.
int SetUpPointer(mjModel* m, const std::string& origin, const std::string& name,
                 std::vector<GeomInfo>* geoms) {
  if (name.empty()) return -1;
  const int body = mj_name2id(m, mjOBJ_BODY, name.c_str());
  if (body < 0) {
    throw SceneError(origin + ": pointer body '" + name + "' not found; " + PointerFix(name));
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
  auto impl = std::make_unique<Impl>();
  internal::InitializeState(LoadOrThrow(origin.c_str(), nullptr, origin, ReadScene(path)), origin, options,
                            impl.get());
  return World(std::move(impl));
}

World World::LoadString(const std::string& xml, const LoadOptions& options,
                        const std::string& origin) {
  // MuJoCo 2.2 loads only from files: stage the text as a file of a virtual file system. Relative
  // asset paths in the text then resolve against the working directory.
  constexpr char kName[] = "mrh_scene.xml";
  // (MuJoCo ends the process on an empty virtual file.)
  if (xml.empty()) {
    throw SceneError(origin + ": the scene text is empty; expected MJCF (<mujoco>...</mujoco>)");
  }
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());

  struct VfsCleanup {
    mjVFS* vfs;

    ~VfsCleanup() { mj_deleteVFS(vfs); }
  } cleanup{vfs.get()};

  if (mj_makeEmptyFileVFS(vfs.get(), kName, static_cast<int>(xml.size())) != 0) {
    throw SceneError(origin + ": cannot stage the scene text for MuJoCo (" +
                     std::to_string(xml.size()) + " bytes)");
  }
  const int file = mj_findFileVFS(vfs.get(), kName);
  std::memcpy(vfs->filedata[file], xml.data(), xml.size());
  auto impl = std::make_unique<Impl>();
  internal::InitializeState(LoadOrThrow(kName, vfs.get(), origin, xml), origin, options, impl.get());
  return World(std::move(impl));
}

namespace internal {

void InitializeState(ModelPtr model, const std::string& origin, const LoadOptions& options,
                     WorldState* impl) {
  impl->origin = origin;
  DescribeModel(*model, origin, &impl->bodies, &impl->geoms);
  impl->pointer_body = SetUpPointer(model.get(), origin, options.pointer_body, &impl->geoms);
  impl->data.reset(mj_makeData(model.get()));
  if (!impl->data) {
    throw SceneError(origin + ": MuJoCo could not allocate the scene's data (njmax " +
                     std::to_string(model->njmax) + ", nconmax " + std::to_string(model->nconmax) +
                     ", nstack " + std::to_string(model->nstack) +
                     "); lower <size> or remove it (mrhaptics sizes the buffers from the scene)");
  }
  impl->model = std::move(model);
  impl->snapshot_size = SnapshotSize(*impl->model);
  // Everything derived from qpos (poses, contacts) is valid right after loading.
  mj_forward(impl->model.get(), impl->data.get());
}

}  // namespace internal
}  // namespace mrh::world
