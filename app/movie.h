// Movies from PNG frames through ffmpeg, shared by `invfree render --mp4/--gif` and
// `invfree modes --mp4`: finding ffmpeg on PATH and running it over DIR/frame_%06d.png.
#pragma once

#include <functional>
#include <string>

namespace invfree {

// The full path of `program` on PATH, or "".
std::string find_on_path(const std::string& program);

// Runs ffmpeg over this run's frames DIR/frame_000000.png .. frame_<frames-1>.png into
// DIR/movie.mp4 (H.264, yuv420p, dimensions padded to even numbers with white, as yuv420p
// needs) or DIR/movie.gif (ffmpeg's palettegen / paletteuse: one palette made for the
// whole clip), or into `movie_path` when it is given (a file in another directory);
// older frames after them (--force) are not part of it. Written under a temporary name,
// checked (check_movie_file) and renamed only when complete: a movie ffmpeg could not
// finish is an error naming it, and nothing is left behind. ffmpeg reports its progress
// on a pipe (-progress): `on_frame(n)` is called with each frame count it reports. An interruption
// reaches ffmpeg too; when it stopped ffmpeg there is no movie and no error. ffmpeg's own
// messages are held in a memory file and shown only when it failed by itself. Returns ""
// or a one-line error; *made tells whether the movie was written.
// What ffmpeg wrote, checked before it is renamed into place: ffmpeg 5.1 exits 0 after a
// write error (a full disk, a file-size limit), leaving an MP4 without its index (moov) or
// a GIF without its trailer. An MP4 must be a sequence of boxes that ends exactly at the
// end of the file with ftyp, moov and mdat among them, and its video track's sample table
// (stsz) must hold `frames` samples; a GIF must have its header, every block complete, at
// least one image and the trailer as its last byte. Returns "" or why the file is no movie.
std::string check_movie_file(const std::string& path, bool gif, int frames);

std::string make_movie(const std::string& ffmpeg, const std::string& dir, int frames, double fps,
                       bool gif, const std::function<void(int)>& on_frame, bool* made,
                       const std::string& movie_path = "");

}  // namespace invfree
