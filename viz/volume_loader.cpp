#include "volume_loader.h"

#include <vtkDataArray.h>
#include <vtkMatrix3x3.h>
#include <vtkNrrdReader.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "grid/channel_table.h"
#include "util/error.h"
#include "vtk_messages.h"

#ifdef VOXR_VIEW_OPENVDB
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedIntArray.h>
#endif

namespace voxr::view {

namespace fs = std::filesystem;

bool Volume::has_array(const std::string& name) const {
  return std::find(arrays.begin(), arrays.end(), name) != arrays.end();
}

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string read_prefix(const fs::path& file, size_t bytes) {
  std::ifstream in(file, std::ios::binary);
  if (!in) fail("{}: cannot open the file", file.string());
  std::string text(bytes, '\0');
  in.read(text.data(), std::streamsize(bytes));
  text.resize(size_t(in.gcount()));
  return text;
}

void check_readable_file(const fs::path& file) {
  std::error_code ec;
  if (!fs::exists(file, ec)) fail("{}: no such file", file.string());
  if (fs::is_directory(file, ec)) fail("{}: is a folder, not a volume file", file.string());
}

// Moves the image's direction into a local-to-world matrix (rotation about the origin) and resets it.
vtkSmartPointer<vtkMatrix4x4> take_direction(vtkImageData* image) {
  vtkMatrix3x3* d = image->GetDirectionMatrix();
  const double* o = image->GetOrigin();
  auto m = vtkSmartPointer<vtkMatrix4x4>::New();
  for (int r = 0; r < 3; ++r) {
    double t = o[r];
    for (int c = 0; c < 3; ++c) {
      m->SetElement(r, c, d->GetElement(r, c));
      t -= d->GetElement(r, c) * o[c];
    }
    m->SetElement(r, 3, t);
  }
  image->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 0, 0, 1);
  return m;
}

// voxr's channels first, in the channel table's order; other arrays follow in file order.
void order_arrays(Volume& v) {
  vtkPointData* pd = v.image->GetPointData();
  for (const ChannelInfo& info : kChannelTable)
    if (pd->GetArray(info.array_name)) v.arrays.push_back(info.array_name);
  for (int i = 0; i < pd->GetNumberOfArrays(); ++i) {
    const char* name = pd->GetArrayName(i);
    if (name && !v.has_array(name)) v.arrays.push_back(name);
  }
}

// ---- .vti ------------------------------------------------------------------------------------------------

Volume load_vti(const fs::path& file) {
  const std::string head = read_prefix(file, 4096);
  if (head.find("<VTKFile") == std::string::npos || head.find("type=\"ImageData\"") == std::string::npos)
    fail("{}: not a VTK XML ImageData file (no <VTKFile type=\"ImageData\"> header)", file.string());

  clear_vtk_errors();
  auto reader = vtkSmartPointer<vtkXMLImageDataReader>::New();
  reader->SetFileName(file.c_str());
  reader->Update();
  if (const std::string err = last_vtk_error(); !err.empty())
    fail("{}: cannot read the volume: {}", file.string(), err);

  Volume v;
  v.source = file;
  v.files = {file};
  v.image = vtkSmartPointer<vtkImageData>::New();
  v.image->ShallowCopy(reader->GetOutput());
  v.to_world = take_direction(v.image);
  order_arrays(v);
  return v;
}

// ---- .nrrd -----------------------------------------------------------------------------------------------

struct NrrdHeader {
  std::map<std::string, std::string> fields;  // keys lower case
  std::string get(const std::string& key) const {
    const auto it = fields.find(key);
    return it == fields.end() ? std::string() : it->second;
  }
};

NrrdHeader read_nrrd_header(const fs::path& file) {
  const std::string head = read_prefix(file, 1 << 16);
  if (head.rfind("NRRD000", 0) != 0) fail("{}: not a NRRD file (no NRRD000x magic line)", file.string());
  NrrdHeader h;
  std::istringstream in(head);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) break;
    if (line[0] == '#') continue;
    const size_t colon = line.find(": ");
    if (colon == std::string::npos) continue;  // key:=value pairs and the like
    h.fields[lower(line.substr(0, colon))] = line.substr(colon + 2);
  }
  return h;
}

// The array name of a NRRD file: voxr writes "content: voxr <channel>".
std::string nrrd_array_name(const NrrdHeader& h, const fs::path& file) {
  std::string content = h.get("content");
  if (content.rfind("voxr ", 0) == 0) return content.substr(5);
  if (!content.empty()) return content;
  return file.stem().string();
}

std::vector<std::string> split_words(const std::string& text) {
  std::vector<std::string> words;
  std::istringstream in(text);
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

// "space directions", one entry per axis: a vector, or nullopt for "none" (a non-spatial axis).
std::optional<std::vector<std::optional<std::array<double, 3>>>> nrrd_directions(const NrrdHeader& h) {
  const std::string text = h.get("space directions");
  std::vector<std::optional<std::array<double, 3>>> axes;
  size_t pos = 0;
  while ((pos = text.find_first_not_of(" \t", pos)) != std::string::npos) {
    if (text.compare(pos, 4, "none") == 0) {
      axes.push_back(std::nullopt);
      pos += 4;
      continue;
    }
    const size_t end = text.find(')', pos);
    if (text[pos] != '(' || end == std::string::npos) return std::nullopt;
    std::array<double, 3> v{};
    std::string inner = text.substr(pos + 1, end - pos - 1);
    std::replace(inner.begin(), inner.end(), ',', ' ');
    std::istringstream in(inner);
    in >> v[0] >> v[1] >> v[2];
    if (!in) return std::nullopt;
    axes.push_back(v);
    pos = end + 1;
  }
  if (axes.empty()) return std::nullopt;
  return axes;
}

// Unit columns of "space directions" when they are not axis aligned; empty otherwise (or when absent).
std::optional<std::array<double, 9>> nrrd_rotation(const NrrdHeader& h) {
  const auto directions = nrrd_directions(h);
  if (!directions) return std::nullopt;
  std::vector<std::array<double, 3>> vectors;
  for (const auto& d : *directions)
    if (d) vectors.push_back(*d);
  if (vectors.size() != 3) return std::nullopt;
  std::array<double, 9> d{};  // row-major, columns are the axes
  bool aligned = true;
  for (int c = 0; c < 3; ++c) {
    const double len = std::sqrt(vectors[c][0] * vectors[c][0] + vectors[c][1] * vectors[c][1] +
                                 vectors[c][2] * vectors[c][2]);
    if (len <= 0.0) return std::nullopt;
    for (int r = 0; r < 3; ++r) {
      d[r * 3 + c] = vectors[c][r] / len;
      if (std::abs(d[r * 3 + c] - (r == c ? 1.0 : 0.0)) > 1e-6) aligned = false;
    }
  }
  if (aligned) return std::nullopt;
  return d;
}

// How a NRRD file's axes map onto a VTK image, as its header says. vtkNrrdReader guesses instead: it takes
// any first axis of 9 or fewer samples for vector components, so an 8x20x20 grid came back as a 20x20x1
// image of 8 components.
struct NrrdLayout {
  int components = 1;  // samples per voxel, from the first axis when it is not a space axis
  std::array<int, 3> dims{1, 1, 1};
  std::array<double, 3> spacing{1.0, 1.0, 1.0};
};

bool is_space_kind(const std::string& kind) {
  return kind == "domain" || kind == "space" || kind == "time";
}

NrrdLayout nrrd_layout(const NrrdHeader& h, const fs::path& file) {
  std::vector<long long> sizes;
  for (const std::string& w : split_words(h.get("sizes"))) {
    char* end = nullptr;
    const long long n = std::strtoll(w.c_str(), &end, 10);
    if (*end != '\0' || n <= 0 || n > std::numeric_limits<int>::max())
      fail("{}: bad 'sizes' entry '{}' in the NRRD header", file.string(), w);
    sizes.push_back(n);
  }
  if (sizes.empty()) fail("{}: the NRRD header has no 'sizes' field", file.string());
  std::vector<std::string> kinds = split_words(lower(h.get("kinds")));
  if (!kinds.empty() && kinds.size() != sizes.size())
    fail("{}: the NRRD header's 'kinds' names {} axes and 'sizes' {}", file.string(), kinds.size(),
         sizes.size());
  const auto directions = nrrd_directions(h);
  const bool directions_per_axis = directions && directions->size() == sizes.size();

  // The first axis holds components when its kind says so (voxr writes "3-vector" there for normals and
  // "domain" for every space axis). Without a kind, NRRD's own hints: a "none" direction, or a 4th axis.
  bool components_first = false;
  const std::string first_kind = kinds.empty() ? "???" : kinds[0];
  if (first_kind == "???" || first_kind == "none")
    components_first = sizes.size() > 3 || (directions_per_axis && !(*directions)[0]);
  else
    components_first = !is_space_kind(first_kind);
  const size_t first_space = components_first ? 1 : 0;
  for (size_t a = first_space; a < kinds.size(); ++a)
    if (kinds[a] != "???" && kinds[a] != "none" && !is_space_kind(kinds[a]))
      fail("{}: NRRD axis {} is of kind '{}'; voxr-view reads vector components on the first axis only",
           file.string(), a, kinds[a]);
  if (sizes.size() - first_space < 1 || sizes.size() - first_space > 3)
    fail("{}: the NRRD file has {} space axes; voxr-view reads 1 to 3", file.string(),
         sizes.size() - first_space);

  NrrdLayout layout;
  if (components_first) layout.components = int(sizes[0]);
  std::vector<double> spacings;
  for (const std::string& w : split_words(h.get("spacings")))
    spacings.push_back(std::strtod(w.c_str(), nullptr));
  for (size_t a = first_space; a < sizes.size(); ++a) {
    const size_t i = a - first_space;
    layout.dims[i] = int(sizes[a]);
    if (directions_per_axis && (*directions)[a]) {
      const auto& v = *(*directions)[a];
      layout.spacing[i] = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    } else if (spacings.size() == sizes.size() && std::isfinite(spacings[a])) {
      layout.spacing[i] = spacings[a];
    }
  }
  return layout;
}

// Reads the samples with vtkNrrdReader and shapes them as the header says. The sample order is the same
// whichever axis VTK took for components (components fastest, then x, y, z), so only the shape changes.
vtkSmartPointer<vtkImageData> read_nrrd_image(const fs::path& file, const NrrdHeader& h) {
  const NrrdLayout layout = nrrd_layout(h, file);
  clear_vtk_errors();
  auto reader = vtkSmartPointer<vtkNrrdReader>::New();
  reader->SetFileName(file.c_str());
  reader->Update();
  if (const std::string err = last_vtk_error(); !err.empty())
    fail("{}: cannot read the volume: {}", file.string(), err);
  vtkImageData* read = reader->GetOutput();
  vtkDataArray* samples = read->GetPointData()->GetScalars();
  if (!samples || read->GetNumberOfPoints() == 0) fail("{}: the NRRD reader returned no data", file.string());
  const vtkIdType expected =
      vtkIdType(layout.components) * layout.dims[0] * layout.dims[1] * vtkIdType(layout.dims[2]);
  if (samples->GetNumberOfValues() != expected)
    fail("{}: the NRRD reader returned {} values where the header's sizes make {}", file.string(),
         samples->GetNumberOfValues(), expected);
  samples->SetNumberOfComponents(layout.components);

  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(layout.dims.data());
  image->SetSpacing(layout.spacing.data());
  image->SetOrigin(read->GetOrigin());
  image->GetPointData()->SetScalars(samples);
  return image;
}

// "out.count.nrrd" -> "out.nrrd" when the stem ends in a voxr channel name and the base file exists.
fs::path nrrd_set_base(const fs::path& file) {
  const fs::path stem(file.stem());
  const std::string suffix = stem.extension().string();  // ".count"
  if (suffix.size() > 1) {
    const std::string channel = suffix.substr(1);
    if (std::any_of(kChannelTable.begin(), kChannelTable.end(),
                    [&](const ChannelInfo& info) { return channel == info.name; })) {
      fs::path base = file.parent_path() / stem.stem();
      base += file.extension();
      std::error_code ec;
      if (fs::is_regular_file(base, ec)) return base;
    }
  }
  return file;
}

Volume load_nrrd(const fs::path& file) {
  read_nrrd_header(file);  // the magic check, before anything else is opened
  const fs::path base = nrrd_set_base(file);
  const NrrdHeader base_header = read_nrrd_header(base);

  Volume v;
  v.source = file;
  v.image = read_nrrd_image(base, base_header);
  v.image->GetPointData()->GetScalars()->SetName(nrrd_array_name(base_header, base).c_str());
  v.files.push_back(base);
  if (const auto rotation = nrrd_rotation(base_header)) v.image->SetDirectionMatrix(rotation->data());

  // Siblings: <stem>.<name><ext> next to the base.
  const std::string prefix = base.stem().string() + ".";
  std::vector<fs::path> siblings;
  std::error_code ec;
  for (const auto& entry :
       fs::directory_iterator(base.parent_path().empty() ? "." : base.parent_path(), ec)) {
    const fs::path p = entry.path();
    const std::string name = p.filename().string();
    if (p.extension() == base.extension() && name.rfind(prefix, 0) == 0 && p.filename() != base.filename() &&
        fs::path(p.stem()).stem() == base.stem())
      siblings.push_back(p);
  }
  std::sort(siblings.begin(), siblings.end());
  const int* dims = v.image->GetDimensions();
  for (const fs::path& p : siblings) {
    const NrrdHeader h = read_nrrd_header(p);
    vtkSmartPointer<vtkImageData> image = read_nrrd_image(p, h);
    const int* d = image->GetDimensions();
    if (d[0] != dims[0] || d[1] != dims[1] || d[2] != dims[2])
      fail("{}: dimensions {}x{}x{} differ from {}'s {}x{}x{}", p.string(), d[0], d[1], d[2],
           base.filename().string(), dims[0], dims[1], dims[2]);
    vtkDataArray* array = image->GetPointData()->GetScalars();
    array->SetName(nrrd_array_name(h, p).c_str());
    if (v.image->GetPointData()->GetArray(array->GetName()))
      fail("{}: array '{}' is already in {}", p.string(), array->GetName(), base.filename().string());
    v.image->GetPointData()->AddArray(array);
    v.files.push_back(p);
  }
  v.to_world = take_direction(v.image);
  order_arrays(v);
  return v;
}

// ---- .vdb ------------------------------------------------------------------------------------------------

#ifdef VOXR_VIEW_OPENVDB

// Index box [lo, lo + dims) of the dense image: [0, voxr_dims) for voxr's files, else the active voxels'
// bounding box of all grids.
struct VdbRegion {
  openvdb::Coord lo{0, 0, 0};
  std::array<int64_t, 3> dims{0, 0, 0};
  uint64_t voxels() const { return uint64_t(dims[0]) * uint64_t(dims[1]) * uint64_t(dims[2]); }
};

VdbRegion vdb_region(const openvdb::GridPtrVec& grids) {
  VdbRegion r;
  for (const auto& g : grids)
    if (const auto meta = g->getMetadata<openvdb::Vec3IMetadata>("voxr_dims")) {
      for (int a = 0; a < 3; ++a) r.dims[a] = std::max<int64_t>(0, meta->value()[a]);
      return r;
    }
  openvdb::CoordBBox box;
  for (const auto& g : grids) box.expand(g->evalActiveVoxelBoundingBox());
  if (box.empty()) return r;
  r.lo = box.min();
  for (int a = 0; a < 3; ++a) r.dims[a] = int64_t(box.max()[a]) - box.min()[a] + 1;
  return r;
}

// Copies the active values of `grid` inside the region into `out` (components per voxel, linear order).
template <typename GridT, typename Store>
void vdb_to_dense(const GridT& grid, const VdbRegion& region, Store&& store) {
  const openvdb::CoordBBox box(
      region.lo,
      region.lo + openvdb::Coord(int(region.dims[0] - 1), int(region.dims[1] - 1), int(region.dims[2] - 1)));
  auto put = [&](const openvdb::Coord& c, const typename GridT::ValueType& v) {
    if (!box.isInside(c)) return;
    const openvdb::Coord d = c - region.lo;
    store(vtkIdType((int64_t(d.z()) * region.dims[1] + d.y()) * region.dims[0] + d.x()), v);
  };
  for (auto it = grid.cbeginValueOn(); it; ++it) {
    if (it.isVoxelValue()) {
      put(it.getCoord(), *it);
      continue;
    }
    openvdb::CoordBBox tile;
    it.getBoundingBox(tile);
    tile.intersect(box);
    for (auto c = tile.begin(); c; ++c) put(*c, *it);
  }
}

Volume load_vdb(const fs::path& file) {
  openvdb::initialize();
  openvdb::GridPtrVecPtr grids;
  try {
    openvdb::io::File f(file.string());
    f.open(false);
    grids = f.getGrids();
    f.close();
  } catch (const std::exception& e) {
    fail("{}: cannot read the OpenVDB file: {}", file.string(), e.what());
  }
  if (!grids || grids->empty()) fail("{}: the OpenVDB file holds no grids", file.string());
  const VdbRegion region = vdb_region(*grids);
  if (region.voxels() == 0) fail("{}: the OpenVDB grids have no active voxels", file.string());

  // The grids voxr-view shows, with the bytes of their dense arrays; the limit is checked before any copy.
  uint64_t bytes = 0;
  for (const auto& g : *grids) {
    if (g->isType<openvdb::BoolGrid>() || g->isType<openvdb::MaskGrid>())
      bytes += 1;
    else if (g->isType<openvdb::Int32Grid>() || g->isType<openvdb::FloatGrid>())
      bytes += 4;
    else if (g->isType<openvdb::Vec3SGrid>())
      bytes += 12;
  }
  if (bytes == 0) fail("{}: no grid voxr-view shows (bool, mask, int32, float, vec3s)", file.string());
  if (region.voxels() * bytes > kMaxDenseVdbBytes)
    fail(
        "{}: {}x{}x{} voxels are {:.1f} GiB as dense arrays, more than voxr-view shows ({} GiB); write a "
        "lower "
        "--res, or .vti of a part (--bounds)",
        file.string(), region.dims[0], region.dims[1], region.dims[2],
        double(region.voxels() * bytes) / double(uint64_t(1) << 30), kMaxDenseVdbBytes >> 30);

  Volume v;
  v.source = file;
  v.files = {file};
  v.image = vtkSmartPointer<vtkImageData>::New();
  v.image->SetDimensions(int(region.dims[0]), int(region.dims[1]), int(region.dims[2]));
  const vtkIdType n = vtkIdType(region.voxels());
  const openvdb::GridBase& first = *grids->front();
  for (const auto& g : *grids) {
    const std::string name = g->getName().empty() ? "grid" : g->getName();
    if (v.image->GetPointData()->GetArray(name.c_str())) continue;
    vtkSmartPointer<vtkDataArray> array;
    if (const auto b = openvdb::GridBase::grid<openvdb::BoolGrid>(g)) {
      auto a = vtkSmartPointer<vtkUnsignedCharArray>::New();
      a->SetNumberOfValues(n);
      a->FillValue(0);
      vdb_to_dense(*b, region, [&](vtkIdType i, bool value) { a->SetValue(i, value ? 1 : 0); });
      array = a;
    } else if (const auto m = openvdb::GridBase::grid<openvdb::MaskGrid>(g)) {
      auto a = vtkSmartPointer<vtkUnsignedCharArray>::New();
      a->SetNumberOfValues(n);
      a->FillValue(0);
      vdb_to_dense(*m, region, [&](vtkIdType i, bool) { a->SetValue(i, 1); });
      array = a;
    } else if (const auto ig = openvdb::GridBase::grid<openvdb::Int32Grid>(g)) {
      // voxr's uint32 channels are stored as int32, bit for bit: shown as unsigned again.
      const ChannelInfo* info = find_channel_array(name);
      if (info && info->type == ElementType::kUInt32) {
        auto a = vtkSmartPointer<vtkUnsignedIntArray>::New();
        a->SetNumberOfValues(n);
        a->FillValue(0);
        vdb_to_dense(*ig, region, [&](vtkIdType i, int32_t value) { a->SetValue(i, uint32_t(value)); });
        array = a;
      } else {
        auto a = vtkSmartPointer<vtkIntArray>::New();
        a->SetNumberOfValues(n);
        a->FillValue(ig->background());
        vdb_to_dense(*ig, region, [&](vtkIdType i, int32_t value) { a->SetValue(i, value); });
        array = a;
      }
    } else if (const auto fg = openvdb::GridBase::grid<openvdb::FloatGrid>(g)) {
      auto a = vtkSmartPointer<vtkFloatArray>::New();
      a->SetNumberOfValues(n);
      a->FillValue(fg->background());
      vdb_to_dense(*fg, region, [&](vtkIdType i, float value) { a->SetValue(i, value); });
      array = a;
    } else if (const auto vg = openvdb::GridBase::grid<openvdb::Vec3SGrid>(g)) {
      auto a = vtkSmartPointer<vtkFloatArray>::New();
      a->SetNumberOfComponents(3);
      a->SetNumberOfTuples(n);
      const openvdb::Vec3s bg = vg->background();
      for (int c = 0; c < 3; ++c) a->FillComponent(c, bg[c]);
      vdb_to_dense(*vg, region,
                   [&](vtkIdType i, const openvdb::Vec3s& value) { a->SetTypedTuple(i, value.asPointer()); });
      array = a;
    } else {
      continue;  // other grid types are not shown
    }
    array->SetName(name.c_str());
    v.image->GetPointData()->AddArray(array);
  }
  if (v.image->GetPointData()->GetNumberOfArrays() > 0)
    v.image->GetPointData()->SetActiveScalars(v.image->GetPointData()->GetArray(0)->GetName());

  // Placement from the first grid's transform (voxr writes one transform for all): image origin = world
  // position of the region's first index, spacing = voxel size, direction = the index axes.
  const openvdb::math::Transform& xform = first.transform();
  if (!xform.isLinear())
    fail("{}: the grids' transform is not linear; voxr-view shows linear ones", file.string());
  const openvdb::Mat4d m = xform.baseMap()->getAffineMap()->getMat4();
  const openvdb::Vec3d origin = xform.indexToWorld(region.lo);
  double spacing[3];
  double direction[9];  // row-major, columns are the index axes
  for (int a = 0; a < 3; ++a) {
    const openvdb::Vec3d axis(m(a, 0), m(a, 1), m(a, 2));
    spacing[a] = axis.length();
    if (spacing[a] <= 0.0) fail("{}: the grids' transform is singular", file.string());
    for (int r = 0; r < 3; ++r) direction[r * 3 + a] = axis[r] / spacing[a];
  }
  v.image->SetSpacing(spacing);
  v.image->SetOrigin(origin.x(), origin.y(), origin.z());
  v.image->SetDirectionMatrix(direction);
  v.to_world = take_direction(v.image);
  order_arrays(v);
  return v;
}

#endif  // VOXR_VIEW_OPENVDB

}  // namespace

Volume load_volume(const fs::path& file) {
  check_readable_file(file);
  const std::string ext = lower(file.extension().string());
  Volume v;
  if (ext == ".vti")
    v = load_vti(file);
  else if (ext == ".nrrd")
    v = load_nrrd(file);
#ifdef VOXR_VIEW_OPENVDB
  else if (ext == ".vdb")
    v = load_vdb(file);
#else
  else if (ext == ".vdb")
    fail("{}: this voxr-view was built without OpenVDB (install libopenvdb-dev, rebuild)", file.string());
#endif
  else if (ext.empty())
    fail("{}: no extension to tell the format by (voxr-view reads .vti, .nrrd and .vdb)", file.string());
  else
    fail("{}: unknown volume format '{}' (voxr-view reads .vti, .nrrd and .vdb)", file.string(),
         file.extension().string());
  if (v.arrays.empty()) fail("{}: holds no point-data arrays", file.string());
  if (v.image->GetNumberOfPoints() <= 0) fail("{}: the volume is empty", file.string());
  return v;
}

}  // namespace voxr::view
