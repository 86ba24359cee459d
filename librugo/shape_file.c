/* placeholder: being written */ typedef int rugo__placeholder_shape_file;
