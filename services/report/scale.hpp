#pragma once
// Maps data values to pixel coordinates along one axis (linear or logarithmic).
namespace ambid::report {

class Scale {
 public:
  // Data [lo, hi] onto pixels [pixel_lo, pixel_hi] (pixel_hi < pixel_lo for a y axis, which
  // grows downwards in SVG). Throws ambid::Error for an empty range or log with lo <= 0.
  Scale(double lo, double hi, double pixel_lo, double pixel_hi, bool log);

  double to_pixel(double value) const;
  // True when the value can be drawn at all (finite, and > 0 on a log axis).
  bool drawable(double value) const;

 private:
  double lo_;
  double hi_;
  double pixel_lo_;
  double pixel_hi_;
  bool log_;
};

}  // namespace ambid::report
