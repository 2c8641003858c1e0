#include "hud.h"

#include <vtkCaptionActor2D.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkScalarsToColors.h>
#include <vtkTextProperty.h>

#include <cmath>

namespace voxr::view {

namespace {

void style_text(vtkTextProperty* p, int size) {
  p->SetFontFamilyToCourier();
  p->SetFontSize(size);
  p->SetColor(0.92, 0.92, 0.92);
  p->SetShadow(1);
}

}  // namespace

Hud::Hud(vtkRenderer* renderer, vtkRenderWindowInteractor* interactor) {
  axes_->SetShaftTypeToCylinder();
  axes_->SetTotalLength(1.0, 1.0, 1.0);
  for (vtkCaptionActor2D* c :
       {axes_->GetXAxisCaptionActor2D(), axes_->GetYAxisCaptionActor2D(), axes_->GetZAxisCaptionActor2D()}) {
    c->GetCaptionTextProperty()->SetShadow(0);
    c->GetCaptionTextProperty()->ItalicOff();
    c->GetCaptionTextProperty()->SetColor(0.95, 0.95, 0.95);
  }
  marker_->SetOrientationMarker(axes_);
  marker_->SetInteractor(interactor);
  marker_->SetDefaultRenderer(renderer);
  marker_->SetViewport(0.0, 0.0, 0.16, 0.2);
  marker_->SetEnabled(1);
  marker_->InteractiveOff();

  bar_->SetOrientationToVertical();
  bar_->SetPosition(0.85, 0.12);
  bar_->SetWidth(0.12);
  bar_->SetHeight(0.6);
  bar_->SetMaximumWidthInPixels(90);
  bar_->SetBarRatio(0.3);
  bar_->UnconstrainedFontSizeOn();
  style_text(bar_->GetTitleTextProperty(), 14);
  style_text(bar_->GetLabelTextProperty(), 12);
  style_text(bar_->GetAnnotationTextProperty(), 12);
  renderer->AddViewProp(bar_);

  style_text(info_->GetTextProperty(), 14);
  info_->GetTextProperty()->SetVerticalJustificationToTop();
  info_->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  info_->GetPositionCoordinate()->SetValue(0.01, 0.985);
  renderer->AddViewProp(info_);

  style_text(hint_->GetTextProperty(), 13);
  hint_->GetTextProperty()->SetJustificationToRight();
  hint_->GetTextProperty()->SetColor(0.7, 0.7, 0.7);
  hint_->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  hint_->GetPositionCoordinate()->SetValue(0.99, 0.015);
  hint_->SetInput("h: keys");
  renderer->AddViewProp(hint_);

  style_text(help_->GetTextProperty(), 15);
  help_->GetTextProperty()->SetBackgroundColor(0.0, 0.0, 0.0);
  help_->GetTextProperty()->SetBackgroundOpacity(0.75);
  help_->GetTextProperty()->SetVerticalJustificationToCentered();
  help_->GetTextProperty()->SetJustificationToCentered();
  help_->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  help_->GetPositionCoordinate()->SetValue(0.5, 0.5);
  help_->SetVisibility(0);
  renderer->AddViewProp(help_);
}

void Hud::set_info(const std::string& text) {
  info_->SetInput(text.c_str());
}

void Hud::set_legend(vtkScalarsToColors* legend, const std::string& title, bool categorical, bool integer) {
  has_legend_ = legend != nullptr;
  bar_->SetVisibility(visible_ && has_legend_ ? 1 : 0);
  if (!legend) return;
  bar_->SetLookupTable(legend);
  bar_->SetTitle(title.c_str());
  bar_->SetDrawAnnotations(categorical ? 1 : 0);
  bar_->SetDrawTickLabels(categorical ? 0 : 1);
  // Whole-number labels: as many (2..5) as divide the range evenly.
  const double* range = legend->GetRange();
  const long span = std::lround(range[1] - range[0]);
  int labels = 5;
  if (integer) {
    labels = 2;
    for (int n = 5; n > 2; --n)
      if (span > 0 && span % (n - 1) == 0) {
        labels = n;
        break;
      }
  }
  bar_->SetNumberOfLabels(labels);
  bar_->SetLabelFormat(integer ? "%.0f" : "%.3g");
}

void Hud::set_help(const std::string& text) {
  help_->SetInput(text.c_str());
}

void Hud::toggle_help() {
  help_shown_ = !help_shown_;
  help_->SetVisibility(help_shown_ ? 1 : 0);
}

void Hud::set_visible(bool visible) {
  visible_ = visible;
  bar_->SetVisibility(visible && has_legend_ ? 1 : 0);
  info_->SetVisibility(visible ? 1 : 0);
  hint_->SetVisibility(visible ? 1 : 0);
  marker_->SetEnabled(visible ? 1 : 0);
  if (visible) marker_->InteractiveOff();
}

}  // namespace voxr::view
