/*
** PNG reading and writing with libpng (pngio.h).
**
** libpng reports errors by calling an error function that must not return;
** ours copies the message into the io record and longjmps back to the
** setjmp in the caller. Our own read and write functions turn short reads
** and failed writes into messages a user can act on. Anything that must be
** freed after such a jump is declared volatile and set before setjmp.
*/
#define _XOPEN_SOURCE 700       /* fileno, fstat */
#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "outfile.h"
#include "pngio.h"

typedef struct pngio {
  FILE *f;
  char msg[200];          /* the last libpng error */
  unsigned char *buf;     /* lsys_pngio_encode: the bytes so far */
  size_t len, cap;
} pngio;

static void onerror (png_structp png, png_const_charp msg) {
  pngio *io = (pngio *)png_get_error_ptr(png);
  snprintf(io->msg, sizeof io->msg, "%s", msg);
  png_longjmp(png, 1);
}

static void onwarning (png_structp png, png_const_charp msg) {
  (void)png; (void)msg;   /* warnings (bad ancillary chunks, ...) are not errors */
}

static void readfn (png_structp png, png_bytep p, size_t n) {
  pngio *io = (pngio *)png_get_io_ptr(png);
  if (fread(p, 1, n, io->f) != n)
    png_error(png, ferror(io->f) ? strerror(errno) : "unexpected end of file");
}

static void writefn (png_structp png, png_bytep p, size_t n) {
  pngio *io = (pngio *)png_get_io_ptr(png);
  if (fwrite(p, 1, n, io->f) != n) png_error(png, strerror(errno));
}

static void flushfn (png_structp png) {
  pngio *io = (pngio *)png_get_io_ptr(png);
  if (fflush(io->f) != 0) png_error(png, strerror(errno));
}

static void memwritefn (png_structp png, png_bytep p, size_t n) {
  pngio *io = (pngio *)png_get_io_ptr(png);
  if (n > (size_t)-1 - io->len ||
      lsys_common_grow((void **)&io->buf, &io->cap, io->len + n, 1) != LSYS_OK)
    png_error(png, "not enough memory");
  memcpy(io->buf + io->len, p, n);
  io->len += n;
}

static void memflushfn (png_structp png) { (void)png; }

/* The image rows, after the header (the caller's setjmp catches libpng's errors). */
static void putimage (png_structp png, png_infop info, const uint8_t *rgba, int w, int h,
                      int alpha) {
  int y;
  png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8,
               alpha ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  if (!alpha) png_set_filler(png, 0, PNG_FILLER_AFTER);   /* drop the 4th byte */
  for (y = 0; y < h; y++) png_write_row(png, rgba + (size_t)4 * w * y);
  png_write_end(png, NULL);
}

int lsys_pngio_encode (const uint8_t *rgba, int w, int h, int alpha, unsigned char **out,
                       size_t *len, lsys_error *e) {
  pngio io = {NULL, "", NULL, 0, 0};
  pngio *volatile iop = &io;
  png_structp png;
  png_infop info;
  *out = NULL;
  *len = 0;
  if (w <= 0 || h <= 0 || w > LSYS_PNG_MAXSIZE || h > LSYS_PNG_MAXSIZE)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "bad image size %dx%d", w, h);
  png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &io, onerror, onwarning);
  info = png ? png_create_info_struct(png) : NULL;
  if (info == NULL) {
    png_destroy_write_struct(&png, NULL);
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    LSYS_FREE(iop->buf);
    return lsys_seterror(e, strcmp(iop->msg, "not enough memory") == 0 ? LSYS_ENOMEM
                         : LSYS_EARG, (size_t)-1, "%s", iop->msg);
  }
  png_set_write_fn(png, &io, memwritefn, memflushfn);
  putimage(png, info, rgba, w, h, alpha);
  png_destroy_write_struct(&png, &info);
  *out = io.buf;
  *len = io.len;
  return LSYS_OK;
}

/* The file is written through an lsys_outfile: a failure leaves whatever was
** at 'path' untouched and removes only the temporary file (outfile.h). */
int lsys_pngio_write (const char *path, const uint8_t *rgba, int w, int h, int alpha,
                      lsys_error *e) {
  pngio io = {NULL, "", NULL, 0, 0};
  lsys_outfile out;
  png_structp png;
  png_infop info;
  int st;
  if (w <= 0 || h <= 0 || w > LSYS_PNG_MAXSIZE || h > LSYS_PNG_MAXSIZE)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot write '%s': bad image size %dx%d",
                         path, w, h);
  if ((st = lsys_outfile_open(&out, path, e)) != LSYS_OK) return st;
  io.f = out.f;
  png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &io, onerror, onwarning);
  info = png ? png_create_info_struct(png) : NULL;
  if (info == NULL) {
    png_destroy_write_struct(&png, NULL);
    lsys_outfile_abort(&out);
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': not enough memory",
                         path);
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    lsys_outfile_abort(&out);
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot write '%s': %s", path, io.msg);
  }
  png_set_write_fn(png, &io, writefn, flushfn);
  putimage(png, info, rgba, w, h, alpha);
  png_destroy_write_struct(&png, &info);
  return lsys_outfile_commit(&out, e);
}

int lsys_pngio_read (const char *path, uint8_t **rgba, int *w, int *h, lsys_error *e) {
  pngio io = {NULL, "", NULL, 0, 0};
  png_structp png;
  png_infop info;
  uint8_t sig[8];
  uint8_t *volatile buf = NULL;
  volatile int code = LSYS_ESYNTAX;
  png_uint_32 pw, ph, y;
  int pass, npass;
  *rgba = NULL;
  *w = *h = 0;
  if ((io.f = fopen(path, "rb")) == NULL)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot open '%s' for reading: %s", path,
                         strerror(errno));
  {
    struct stat st;
    if (fstat(fileno(io.f), &st) != 0 || !S_ISREG(st.st_mode)) {
      fclose(io.f);
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot read '%s': %s", path,
                           S_ISDIR(st.st_mode) ? strerror(EISDIR) : "not a regular file");
    }
  }
  if (fread(sig, 1, sizeof sig, io.f) != sizeof sig || png_sig_cmp(sig, 0, sizeof sig)) {
    int err = ferror(io.f) ? errno : 0;
    fclose(io.f);
    if (err)
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot read '%s': %s", path,
                           strerror(err));
    return lsys_seterror(e, LSYS_ESYNTAX, (size_t)-1, "'%s' is not a PNG file", path);
  }
  png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &io, onerror, onwarning);
  info = png ? png_create_info_struct(png) : NULL;
  if (info == NULL) {
    png_destroy_read_struct(&png, NULL, NULL);
    fclose(io.f);
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot read '%s': not enough memory",
                         path);
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, NULL);
    fclose(io.f);
    LSYS_FREE(buf);
    return lsys_seterror(e, code, (size_t)-1, "cannot read '%s': %s", path, io.msg);
  }
  png_set_read_fn(png, &io, readfn);
  png_set_sig_bytes(png, sizeof sig);
  /* A chunk may declare any length, and libpng 1.6.39 allocates a text or ICC chunk
  ** whole before it reads it (a 53-byte file declaring 1.9 GB of tEXt): the
  ** ancillary chunks lsys has no use for are skipped unread, the others limited. */
  {
    static const png_byte skip[] = "tEXt\0zTXt\0iTXt\0iCCP\0sPLT\0eXIf\0";
    png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_NEVER, skip, (int)(sizeof skip / 5));
    png_set_chunk_malloc_max(png, (png_alloc_size_t)8 << 20);
  }
  png_read_info(png, info);
  pw = png_get_image_width(png, info);
  ph = png_get_image_height(png, info);
  if (pw > LSYS_PNG_MAXSIZE || ph > LSYS_PNG_MAXSIZE) {
    code = LSYS_ELIMIT;
    snprintf(io.msg, sizeof io.msg, "%lux%lu pixels is larger than the limit of %d",
             (unsigned long)pw, (unsigned long)ph, LSYS_PNG_MAXSIZE);
    png_longjmp(png, 1);
  }
  if ((double)pw * ph * 4 > (double)lsys_common_memory_limit()) {    /* before decoding */
    char b1[32], b2[32];
    code = LSYS_EMEMORY;
    snprintf(io.msg, sizeof io.msg, "%lux%lu pixels need %s, more than max_memory (%s)",
             (unsigned long)pw, (unsigned long)ph, lsys_common_fmtsize(b1, (size_t)4 * pw * ph),
             lsys_common_fmtsize(b2, lsys_common_memory_limit()));
    png_longjmp(png, 1);
  }
  /* whatever the file holds, deliver 8-bit RGBA */
  png_set_expand(png);                  /* palette -> RGB, grey < 8 bits -> 8, tRNS -> alpha */
  png_set_strip_16(png);
  png_set_gray_to_rgb(png);
  png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
  npass = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != (size_t)4 * pw) {
    snprintf(io.msg, sizeof io.msg, "unsupported pixel format");
    png_longjmp(png, 1);
  }
  buf = (uint8_t *)LSYS_MALLOC((size_t)4 * pw * ph);
  if (buf == NULL) {
    code = LSYS_ENOMEM;
    snprintf(io.msg, sizeof io.msg, "not enough memory for %lux%lu pixels",
             (unsigned long)pw, (unsigned long)ph);
    png_longjmp(png, 1);
  }
  /* an interlaced image is read in several passes over the same rows */
  for (pass = 0; pass < npass; pass++)
    for (y = 0; y < ph; y++) png_read_row(png, buf + (size_t)4 * pw * y, NULL);
  png_read_end(png, NULL);
  png_destroy_read_struct(&png, &info, NULL);
  fclose(io.f);
  *rgba = buf;
  *w = (int)pw;
  *h = (int)ph;
  return LSYS_OK;
}
