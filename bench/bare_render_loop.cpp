#include "bench/bare_render_loop.h"

#ifdef SPINFOLD_HAVE_OSMESA  // the bare loop is OSMesa's, GL linked by name; libpng is always here
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#endif
#include <png.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace spinfold::bench {

namespace {

const char* kVertex =
    "#version 330 core\nlayout(location=0) in vec3 p;\nlayout(location=1) in vec4 c;\nuniform mat4 m;\nout "
    "vec4 v;\n"
    "void main(){v=c;gl_Position=m*vec4(p,1.0);}\n";
const char* kFragment = "#version 330 core\nin vec4 v;\nout vec4 f;\nvoid main(){f=v;}\n";

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void sink(png_structp png, png_bytep data, png_size_t n) {
  auto* out = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + n);
}

std::vector<unsigned char> encode_with_libpng(const unsigned char* rgba, int w, int h) {
  std::vector<unsigned char> out, row(static_cast<std::size_t>(w) * 3);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_set_write_fn(png, &out, sink, nullptr);
  png_set_compression_level(png, 1);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
  png_set_IHDR(png, info, w, h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) row[3 * x + c] = rgba[(static_cast<std::size_t>(y) * w + x) * 4 + c];
    png_write_row(png, row.data());
  }
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return out;
}

}  // namespace

#ifdef SPINFOLD_HAVE_OSMESA
BareTimings bare_render_loop(int width, int height, const std::vector<float>& opaque,
                             const std::vector<float>& translucent, const std::vector<float>& lines,
                             const float* view_projection, int frames) {
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            3,
                            0};
  OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!context) throw std::runtime_error("OSMesa context");
  std::vector<unsigned char> buffer(static_cast<std::size_t>(width) * height * 4);
  OSMesaMakeCurrent(context, buffer.data(), GL_UNSIGNED_BYTE, width, height);
  OSMesaPixelStore(OSMESA_Y_UP, 0);

  const GLuint program = glCreateProgram();
  for (auto [type, source] : {std::pair{GL_VERTEX_SHADER, kVertex}, {GL_FRAGMENT_SHADER, kFragment}}) {
    const GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &source, nullptr);
    glCompileShader(s);
    glAttachShader(program, s);
  }
  glLinkProgram(program);
  GLuint vao[3], vbo[3];
  glGenVertexArrays(3, vao);
  glGenBuffers(3, vbo);
  const std::vector<float>* data[3] = {&opaque, &translucent, &lines};
  for (int k = 0; k < 3; ++k) {
    glBindVertexArray(vao[k]);
    glBindBuffer(GL_ARRAY_BUFFER, vbo[k]);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data[k]->size() * sizeof(float)), data[k]->data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 28, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 28, reinterpret_cast<void*>(12));
  }
  std::vector<double> render, enc;
  for (int f = 0; f < frames + 2; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    glViewport(0, 0, width, height);
    glClearColor(0.97f, 0.97f, 0.96f, 1.0f);
    glEnable(GL_DEPTH_TEST);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(program);
    glUniformMatrix4fv(glGetUniformLocation(program, "m"), 1, GL_FALSE, view_projection);
    glBindVertexArray(vao[0]);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(opaque.size() / 7));
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glBindVertexArray(vao[1]);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(translucent.size() / 7));
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glBindVertexArray(vao[2]);
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(lines.size() / 7));
    glFinish();
    const auto t1 = std::chrono::steady_clock::now();
    const std::vector<unsigned char> png = encode_with_libpng(buffer.data(), width, height);
    const auto t2 = std::chrono::steady_clock::now();
    if (f >= 2) {  // the first frames compile the shaders
      render.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      enc.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
    }
  }
  glDeleteBuffers(3, vbo);
  glDeleteVertexArrays(3, vao);
  glDeleteProgram(program);
  OSMesaDestroyContext(context);
  return {median(render), median(enc)};
}

#endif

std::vector<unsigned char> bare_encode_png(const unsigned char* rgba, int width, int height) {
  return encode_with_libpng(rgba, width, height);
}

}  // namespace spinfold::bench
