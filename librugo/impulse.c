/* Placeholder: being written. */
typedef int rugo__placeholder_impulse;
