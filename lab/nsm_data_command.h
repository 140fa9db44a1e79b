#pragma once
// nsm_data's command line as data: its flags declared on a CommandLine and, after parsing, the
// data set parameters they describe. programs/nsm_data.cpp and the Python module (python/) read
// the same flags through it, so both accept and refuse the same input with the same message.
#include <string>

#include "lab/cli.h"
#include "lab/nsm_dataset.h"

namespace shadowlab {

struct NsmDataCommand {
  CommonOptions common;
  NsmDatasetParams params;
  std::string scenes = "default", crop = "256,192", val = "0.1", test = "0.1", features = "all";
  int seed = 1;
};

// Declares the common flags (most marked unused: the trajectories place the views and lights)
// and nsm_data's own on cl, bound to cmd.
void add_nsm_data_flags(CommandLine& cl, NsmDataCommand& cmd);
// After parse_command_line: the frame size, crop, scenes, splits and features into cmd.params,
// checked (check_nsm_dataset_params). Throws InputError naming the flag.
void finish_nsm_data_command(NsmDataCommand& cmd);

}  // namespace shadowlab
