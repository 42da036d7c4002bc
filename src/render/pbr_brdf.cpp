// Filled by its part of issue 30.
