#pragma once
// Output paths checked before any work starts, so that a run cannot destroy its own input, two
// outputs cannot overwrite each other, and an output that cannot be written fails the run at
// once instead of after hours of tracking (leaving the outputs written before it behind).
#include <string>
#include <vector>

namespace vtrack::apps {

// A path with the name the user gave it by ("--out", "render", "video", ...), for messages.
struct NamedPath {
  std::string name;
  std::string path;
  bool folder = false;  // outputs: a folder of files (created with its parents if missing)
};

// Checks every output against the inputs and the other outputs:
//  - InvalidArgument when an output is empty, is the same file or folder as an input (also
//    through symbolic links, "." and ".."), is the same as another output, or when a file output
//    is an existing folder (a folder output an existing file);
//  - IoError when a file output's folder does not exist or is not writable (for a folder
//    output: its nearest existing ancestor).
// Messages name both options and the path, e.g. "--render 'in.avi' is the input VIDEO".
// Inputs that do not exist are skipped (their own reader reports them).
void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

}  // namespace vtrack::apps
