#include "cli/enrollment_report_text.h"

#include <cmath>
#include <cstdio>

namespace orbit::cli {
namespace {

std::string Degrees(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", std::round(value * 10) / 10);
  return text;
}

}  // namespace

std::string EnrollmentReportText(const v1::EnrollmentReport& report) {
  std::string text;
  if (report.gaps_size() == 0) {
    text += "  coverage: no gap wider than 30 degrees\n";
  } else {
    text += "  coverage: " + std::to_string(report.gaps_size()) + " gap" +
            (report.gaps_size() > 1 ? "s" : "") + " wider than 30 degrees:";
    for (int i = 0; i < report.gaps_size(); ++i) {
      const v1::AzimuthGap& gap = report.gaps(i);
      double width = std::fmod(gap.to_deg() - gap.from_deg() + 360, 360);
      if (width == 0) width = 360;
      text += (i > 0 ? ", " : " ") + Degrees(gap.from_deg()) + "-" + Degrees(gap.to_deg()) + " (" +
              Degrees(width) + ")";
    }
    text += "\n";
  }
  if (report.redundant_azimuths_deg_size() > 0) {
    text += "  repeats: " + std::to_string(report.redundant_azimuths_deg_size()) + " view" +
            (report.redundant_azimuths_deg_size() > 1 ? "s add" : " adds") + " nothing (at";
    for (int i = 0; i < report.redundant_azimuths_deg_size(); ++i) {
      text += (i > 0 ? ", " : " ") + Degrees(report.redundant_azimuths_deg(i));
    }
    text += " degrees)\n";
  }
  if (report.confusable_size() > 0) {
    text += "  confusable:";
    for (int i = 0; i < report.confusable_size(); ++i) {
      const v1::ConfusableObject& object = report.confusable(i);
      char numbers[96];
      if (object.closer_views() > 0) {
        std::snprintf(numbers, sizeof numbers, " (similarity %.3f, %d view%s closer than its own)",
                      object.similarity(), object.closer_views(),
                      object.closer_views() > 1 ? "s" : "");
      } else {
        std::snprintf(numbers, sizeof numbers, " (similarity %.3f)", object.similarity());
      }
      text += (i > 0 ? ", " : " ") +
              (object.name().empty() ? "id " + std::to_string(object.id()) : object.name()) +
              numbers;
    }
    text += "\n";
  }
  return text;
}

}  // namespace orbit::cli
