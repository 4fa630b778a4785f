#include "output/png_render.h"

#include <cairo.h>
#include <librsvg/rsvg.h>

#include <cmath>
#include <memory>
#include <ostream>

#include "core/base/error.h"
#include "output/atomic_file.h"

namespace ilp {
namespace {

constexpr double kMaxSide_px = 16384.0;

struct HandleDeleter {
  void operator()(RsvgHandle* h) const { g_object_unref(h); }
};
struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};

// The message of a GError, which is then freed.
std::string take_message(GError* error) {
  std::string message = error != nullptr && error->message != nullptr ? error->message : "unknown error";
  if (error != nullptr) g_error_free(error);
  return message;
}

cairo_status_t write_to_stream(void* closure, const unsigned char* data, unsigned int length) {
  auto* out = static_cast<std::ostream*>(closure);
  out->write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
  return *out ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

}  // namespace

void write_png_from_svg(const std::string& path_png, const std::string& svg, double scale) {
  if (!(scale > 0.0) || scale > 16.0) throw IlpError(path_png + ": PNG scale must be in (0, 16]");
  GError* error = nullptr;
  std::unique_ptr<RsvgHandle, HandleDeleter> handle(
      rsvg_handle_new_from_data(reinterpret_cast<const guint8*>(svg.data()), svg.size(), &error));
  if (!handle) throw IlpError(path_png + ": cannot read the SVG to render (" + take_message(error) + ")");
  gdouble width_svg = 0.0, height_svg = 0.0;
  if (!rsvg_handle_get_intrinsic_size_in_pixels(handle.get(), &width_svg, &height_svg) || !(width_svg > 0.0) ||
      !(height_svg > 0.0))
    throw IlpError(path_png + ": the SVG has no width and height in px");
  const double width_px = std::round(width_svg * scale), height_px = std::round(height_svg * scale);
  if (width_px < 1.0 || height_px < 1.0 || width_px > kMaxSide_px || height_px > kMaxSide_px)
    throw IlpError(path_png + ": a PNG of " + std::to_string(width_px) + " x " + std::to_string(height_px) +
                   " pixels is out of range (1 to 16384 a side)");

  std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface(
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, static_cast<int>(width_px), static_cast<int>(height_px)));
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw IlpError(path_png + ": cannot create the image (" + cairo_status_to_string(cairo_surface_status(surface.get())) + ")");
  std::unique_ptr<cairo_t, ContextDeleter> cr(cairo_create(surface.get()));
  cairo_set_source_rgb(cr.get(), 1.0, 1.0, 1.0);
  cairo_paint(cr.get());
  const RsvgRectangle viewport{0.0, 0.0, width_px, height_px};
  if (!rsvg_handle_render_document(handle.get(), cr.get(), &viewport, &error))
    throw IlpError(path_png + ": cannot render the SVG (" + take_message(error) + ")");
  cairo_surface_flush(surface.get());
  if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS)
    throw IlpError(path_png + ": rendering failed (" + cairo_status_to_string(cairo_status(cr.get())) + ")");

  write_file_atomically(path_png, [&](std::ostream& out) {
    if (cairo_surface_write_to_png_stream(surface.get(), write_to_stream, &out) != CAIRO_STATUS_SUCCESS)
      throw IlpError(path_png + ": write failed");
  });
}

}  // namespace ilp
