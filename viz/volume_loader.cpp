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

}  // namespace

Volume load_volume(const fs::path& file) {
  check_readable_file(file);
  const std::string ext = lower(file.extension().string());
  Volume v;
  if (ext == ".vti")
    v = load_vti(file);
  else if (ext == ".nrrd")
    v = load_nrrd(file);
  else if (ext.empty())
    fail("{}: no extension to tell the format by (voxr-view reads .vti and .nrrd)", file.string());
  else
    fail("{}: unknown volume format '{}' (voxr-view reads .vti and .nrrd)", file.string(),
         file.extension().string());
  if (v.arrays.empty()) fail("{}: holds no point-data arrays", file.string());
  if (v.image->GetNumberOfPoints() <= 0) fail("{}: the volume is empty", file.string());
  return v;
}

}  // namespace voxr::view
