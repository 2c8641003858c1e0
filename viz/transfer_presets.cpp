#include "transfer_presets.h"

#include <vtkLookupTable.h>
#include <vtkVariant.h>

#include <algorithm>
#include <array>
#include <string>

namespace voxr::view {

namespace {

using Rgb = std::array<double, 3>;

constexpr Rgb kOccupied{0.93, 0.86, 0.72};
constexpr Rgb kInside{0.55, 0.75, 0.95};

// Tableau 10: distinct, readable on the dark background.
constexpr std::array<Rgb, 10> kCategories{{{0.12, 0.47, 0.71},
                                           {1.00, 0.50, 0.05},
                                           {0.17, 0.63, 0.17},
                                           {0.84, 0.15, 0.16},
                                           {0.58, 0.40, 0.74},
                                           {0.55, 0.34, 0.29},
                                           {0.89, 0.47, 0.76},
                                           {0.74, 0.74, 0.13},
                                           {0.09, 0.75, 0.81},
                                           {0.60, 0.60, 0.60}}};

// Heat ramp (inferno-like, starting brighter so that low values show on the dark background); t in [0, 1].
constexpr std::array<std::pair<double, Rgb>, 5> kHeat{{{0.00, {0.45, 0.10, 0.58}},
                                                       {0.30, {0.76, 0.16, 0.46}},
                                                       {0.55, {0.95, 0.36, 0.20}},
                                                       {0.80, {0.99, 0.66, 0.05}},
                                                       {1.00, {0.99, 0.98, 0.64}}}};

void add_ramp(vtkColorTransferFunction* f, double lo, double hi) {
  for (const auto& [t, c] : kHeat) f->AddRGBPoint(lo + t * (hi - lo), c[0], c[1], c[2]);
}

void add_cool_warm(vtkColorTransferFunction* f) {
  f->AddRGBPoint(-1.0, 0.23, 0.30, 0.75);
  f->AddRGBPoint(0.0, 0.87, 0.87, 0.87);
  f->AddRGBPoint(1.0, 0.71, 0.02, 0.15);
}

vtkSmartPointer<vtkLookupTable> categorical_legend(const std::vector<std::pair<long, std::string>>& entries,
                                                   const std::vector<Rgb>& colors) {
  auto lut = vtkSmartPointer<vtkLookupTable>::New();
  lut->IndexedLookupOn();
  lut->SetNumberOfTableValues(vtkIdType(entries.size()));
  for (size_t i = 0; i < entries.size(); ++i) {
    lut->SetTableValue(vtkIdType(i), colors[i][0], colors[i][1], colors[i][2], 1.0);
    lut->SetAnnotation(vtkVariant(entries[i].first), entries[i].second);
  }
  return lut;
}

}  // namespace

TransferPreset make_preset(const DisplayField& field, double opacity_scale) {
  TransferPreset p;
  p.color = vtkSmartPointer<vtkColorTransferFunction>::New();
  p.opacity = vtkSmartPointer<vtkPiecewiseFunction>::New();
  auto& color = *p.color;
  auto& opacity = *p.opacity;
  const double empty = field.empty_value;
  auto scaled = [&](double a) { return std::clamp(a * opacity_scale, 0.0, 1.0); };
  auto continuous_legend = [&](double lo, double hi) {
    auto legend = vtkSmartPointer<vtkColorTransferFunction>::New();
    double node[6];
    for (int i = 0; i < color.GetSize(); ++i) {
      color.GetNodeValue(i, node);
      if (node[0] >= lo && node[0] <= hi) legend->AddRGBPoint(node[0], node[1], node[2], node[3]);
    }
    return legend;
  };

  switch (field.kind) {
    case ChannelKind::kOccupancy: {
      // Unshaded and translucent (see the header); the iso view shows the shell as a lit surface.
      color.AddRGBPoint(0.0, kEmptyVoxel[0], kEmptyVoxel[1], kEmptyVoxel[2]);
      color.AddRGBPoint(1.0, kOccupied[0], kOccupied[1], kOccupied[2]);
      opacity.AddPoint(0.0, 0.0);
      opacity.AddPoint(1.0, scaled(0.3));
      p.legend = categorical_legend({{1, "occupied"}}, {kOccupied});
      break;
    }
    case ChannelKind::kInside: {
      // A solid: lit surface where the interior starts (linear sampling, opacity step at 0.5).
      color.AddRGBPoint(0.0, kEmptyVoxel[0], kEmptyVoxel[1], kEmptyVoxel[2]);
      color.AddRGBPoint(1.0, kInside[0], kInside[1], kInside[2]);
      opacity.AddPoint(0.0, 0.0);
      opacity.AddPoint(0.3, 0.0);
      opacity.AddPoint(0.7, scaled(1.0));
      opacity.AddPoint(1.0, scaled(1.0));
      p.legend = categorical_legend({{1, "inside"}}, {kInside});
      p.shade = true;
      break;
    }
    case ChannelKind::kCount: {
      const double lo = std::max(field.low, 1e-6);
      const double hi = std::max(field.robust_high, lo + 1.0);
      color.AddRGBPoint(empty, kEmptyVoxel[0], kEmptyVoxel[1], kEmptyVoxel[2]);
      add_ramp(&color, lo, hi);
      opacity.AddPoint(empty, 0.0);
      opacity.AddPoint(lo, scaled(0.2));
      opacity.AddPoint(hi, scaled(0.95));
      p.legend = continuous_legend(lo, hi);
      break;
    }
    case ChannelKind::kNormal: {
      color.AddRGBPoint(empty, kEmptyVoxel[0], kEmptyVoxel[1], kEmptyVoxel[2]);
      add_cool_warm(&color);
      // Nodes far apart keep VTK's opacity table small; nearest sampling never sees values in (-2, -1).
      opacity.AddPoint(empty, 0.0);
      opacity.AddPoint(-1.5, 0.0);
      opacity.AddPoint(-1.0, scaled(0.85));
      opacity.AddPoint(1.0, scaled(0.85));
      p.legend = continuous_legend(-1.0, 1.0);
      p.categorical = true;  // values of neighbouring voxels must not blend with the empty value
      break;
    }
    case ChannelKind::kMaterial: {
      color.AddRGBPoint(empty, kEmptyVoxel[0], kEmptyVoxel[1], kEmptyVoxel[2]);
      opacity.AddPoint(empty, 0.0);
      opacity.AddPoint(empty + 0.5, 0.0);
      opacity.AddPoint(empty + 1.0, scaled(0.6));
      opacity.AddPoint(std::max(field.high, empty + 1.0), scaled(0.6));
      if (!field.categories.empty()) {
        std::vector<std::pair<long, std::string>> entries;
        std::vector<Rgb> colors;
        for (long id : field.categories) {
          const Rgb& c = kCategories[size_t(id < 0 ? -id : id) % kCategories.size()];
          color.AddRGBPoint(double(id), c[0], c[1], c[2]);
          entries.emplace_back(id, std::to_string(id));
          colors.push_back(c);
        }
        p.legend = categorical_legend(entries, colors);
      } else {
        add_ramp(&color, field.low, std::max(field.high, field.low + 1.0));
        p.legend = continuous_legend(field.low, std::max(field.high, field.low + 1.0));
      }
      p.categorical = true;
      break;
    }
    case ChannelKind::kColor: {
      // The colours are drawn directly; the volume's opacity reads the alpha component (0 empty, 255 set).
      color.AddRGBPoint(0.0, 0.0, 0.0, 0.0);
      color.AddRGBPoint(255.0, 1.0, 1.0, 1.0);
      opacity.AddPoint(0.0, 0.0);
      opacity.AddPoint(127.0, 0.0);
      opacity.AddPoint(128.0, scaled(0.85));
      opacity.AddPoint(255.0, scaled(0.85));
      p.categorical = true;
      break;
    }
    case ChannelKind::kGeneric: {
      const double lo = field.low, hi = std::max(field.high, field.low + 1e-6);
      color.AddRGBPoint(std::min(empty, lo), kEmptyVoxel[0], kEmptyVoxel[1], kEmptyVoxel[2]);
      add_ramp(&color, lo, hi);
      opacity.AddPoint(std::min(empty, lo), 0.0);
      opacity.AddPoint(hi, scaled(0.8));
      p.legend = continuous_legend(lo, hi);
      break;
    }
  }
  return p;
}

}  // namespace voxr::view
