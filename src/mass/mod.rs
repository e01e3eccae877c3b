//! Paper 4: Kim, Kim, Ko & Terzopoulos, "Fast GPU computation of the mass properties of a
//! general shape and its application to buoyancy simulation", The Visual Computer 22(8), 2006.
