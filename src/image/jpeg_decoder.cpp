// JPEG through libjpeg-turbo (Debian's libjpeg62-turbo), from memory. The
// header is read first and the texel limit checked before any scan is decoded;
// a progressive file may have at most 500 scans (libjpeg-turbo's own
// TJFLAG_LIMITSCANS bound: more is a known way to burn CPU on a few bytes),
// and a file that ends early is an error, not a grey-padded picture.
// Output: grey (1 channel) or RGB; Adobe CMYK/YCCK become RGB by stb_image's
// rule (R = C * K / 255 on the stored, inverted, values). Pixel values are
// libjpeg's (accurate integer IDCT, fancy upsampling), which differ from
// stb_image's own decoder by a unit or so in some samples: the two IDCTs and
// YCbCr conversions round differently.
// libjpeg reports errors by longjmp: the function that calls setjmp constructs
// every object with a destructor before it, so the jump skips none.
#include "rayform/image/image_decoders.h"

#include <cstdio>  // jpeglib.h needs FILE
#include <jerror.h>
#include <jpeglib.h>

#include <csetjmp>
#include <cstring>
#include <vector>

namespace rayform {

namespace {

constexpr int max_scans = 500;
constexpr uint64_t sequential_ratio = 256;

struct JpegErrors {
  jpeg_error_mgr mgr;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

JpegErrors* errors_of(j_common_ptr cinfo) { return reinterpret_cast<JpegErrors*>(cinfo->err); }

void jpeg_on_error(j_common_ptr cinfo) {
  JpegErrors* e = errors_of(cinfo);
  cinfo->err->format_message(cinfo, e->message);
  std::longjmp(e->jump, 1);
}

// Warnings (level -1) about corrupt data are tolerated, as every viewer does,
// except a premature end of the file: libjpeg would pad the rest with grey.
void jpeg_on_message(j_common_ptr cinfo, int level) {
  if (level == -1 && cinfo->err->msg_code == JWRN_JPEG_EOF) jpeg_on_error(cinfo);
}

void jpeg_on_progress(j_common_ptr cinfo) {
  if (!cinfo->is_decompressor) return;
  j_decompress_ptr d = reinterpret_cast<j_decompress_ptr>(cinfo);
  if (d->input_scan_number > max_scans) {
    std::snprintf(errors_of(cinfo)->message, JMSG_LENGTH_MAX, "more than %d progressive scans", max_scans);
    std::longjmp(errors_of(cinfo)->jump, 1);
  }
}

struct JpegHandle {
  jpeg_decompress_struct cinfo{};
  volatile bool created = false;  // (volatile: set after setjmp, read after a longjmp)
  ~JpegHandle() {
    if (created) jpeg_destroy_decompress(&cinfo);
  }
};

// stb_image's stbi__blinn_8x8: x * y / 255, rounded.
uint8_t blinn_8x8(unsigned x, unsigned y) {
  unsigned t = x * y + 128;
  return uint8_t((t + (t >> 8)) >> 8);
}

}  // namespace

bool is_jpeg(const uint8_t* bytes, size_t size) {
  return size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

DecodeResult decode_jpeg(const uint8_t* bytes, size_t size, const DecodeOptions& options, DecodedImage* out,
                         std::string* error) {
  JpegErrors errors{};
  JpegHandle h;
  jpeg_progress_mgr progress{};
  std::vector<uint8_t> cmyk_row;
  h.cinfo.err = jpeg_std_error(&errors.mgr);
  errors.mgr.error_exit = jpeg_on_error;
  errors.mgr.emit_message = jpeg_on_message;
  if (setjmp(errors.jump)) {
    *error = errors.message[0] ? errors.message : "corrupt JPEG data";
    out->bytes.clear();
    return DecodeResult::corrupt;
  }
  jpeg_create_decompress(&h.cinfo);
  h.created = true;
  progress.progress_monitor = jpeg_on_progress;
  h.cinfo.progress = &progress;
  jpeg_mem_src(&h.cinfo, bytes, static_cast<unsigned long>(size));
  jpeg_read_header(&h.cinfo, TRUE);
  out->width = int(h.cinfo.image_width);  // at most 65500 a side (JPEG_MAX_DIMENSION)
  out->height = int(h.cinfo.image_height);
  out->bits = 8;
  if (exceeds_texel_limit(h.cinfo.image_width, h.cinfo.image_height, options)) return DecodeResult::too_large;
  const uint64_t texels = uint64_t(h.cinfo.image_width) * h.cinfo.image_height;
  // Sequential Huffman-coded data takes at least 2 bits (a DC and an
  // end-of-block code) for each 8x8 block of the full-resolution component:
  // 256 texels a byte. Progressive and arithmetic-coded files have no such
  // bound (a refinement scan may be missing); their coefficients are charged.
  const bool buffered = h.cinfo.progressive_mode || h.cinfo.arith_code;
  if (!buffered && texels > sequential_ratio * size) {
    std::snprintf(errors.message, JMSG_LENGTH_MAX,
                  "the header declares %ux%u texels, more than its %zu bytes can hold (sequential JPEG data holds at "
                  "most %u texels a byte)",
                  h.cinfo.image_width, h.cinfo.image_height, size, unsigned(sequential_ratio));
    std::longjmp(errors.jump, 1);
  }

  const bool cmyk = h.cinfo.jpeg_color_space == JCS_CMYK || h.cinfo.jpeg_color_space == JCS_YCCK;
  const bool grey = h.cinfo.jpeg_color_space == JCS_GRAYSCALE;
  h.cinfo.out_color_space = cmyk ? JCS_CMYK : grey ? JCS_GRAYSCALE : JCS_RGB;
  h.cinfo.dct_method = JDCT_ISLOW;
  h.cinfo.do_fancy_upsampling = TRUE;
  // The samples, and a progressive file's coefficients (64 16-bit values an
  // 8x8 block: 2 bytes a sample of each component, before subsampling).
  if (!charge_decode(texels * (grey ? 1 : 3) + (buffered ? 2 * texels * uint64_t(h.cinfo.num_components) : 0), options,
                     out, error))
    return DecodeResult::over_budget;
  jpeg_start_decompress(&h.cinfo);
  out->channels = grey ? 1 : 3;
  const size_t stride = size_t(h.cinfo.output_width) * size_t(out->channels);
  if (h.cinfo.output_components != (cmyk ? 4 : out->channels)) std::longjmp(errors.jump, 1);

  out->bytes.resize(stride * h.cinfo.output_height);
  if (cmyk) cmyk_row.resize(size_t(h.cinfo.output_width) * 4);
  while (h.cinfo.output_scanline < h.cinfo.output_height) {
    uint8_t* row = out->bytes.data() + size_t(h.cinfo.output_scanline) * stride;
    JSAMPROW target = cmyk ? cmyk_row.data() : row;
    jpeg_read_scanlines(&h.cinfo, &target, 1);
    if (cmyk)
      for (size_t x = 0; x < h.cinfo.output_width; ++x) {
        const uint8_t* p = &cmyk_row[x * 4];
        for (int k = 0; k < 3; ++k) row[x * 3 + size_t(k)] = blinn_8x8(p[k], p[3]);
      }
  }
  jpeg_finish_decompress(&h.cinfo);
  return DecodeResult::ok;
}

}  // namespace rayform
