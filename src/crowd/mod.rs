//! Paper 2: Kang & Han, "Real-Time Animation of Large Crowds", ICEC 2006.
