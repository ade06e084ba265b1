// replaced by the generator implementation
