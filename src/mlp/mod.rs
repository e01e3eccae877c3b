//! Paper 3: Oh & Jung, "GPU implementation of neural networks", Pattern Recognition 37(6), 2004.
